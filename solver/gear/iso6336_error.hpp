#pragma once
// A rating input ISO 6336 cannot rate: each issue names the JSON pointer of
// the field concerned and says why in one sentence, like a refused job.
#include <stdexcept>
#include <string>
#include <vector>

namespace gearsph::gear::iso6336 {

struct RatingIssue {
  std::string pointer;  // RFC 6901 pointer into the rating document ("" is the root)
  std::string message;  // one sentence
};

class InvalidRating : public std::runtime_error {
 public:
  explicit InvalidRating(std::vector<RatingIssue> list);
  InvalidRating(const std::string& pointer, const std::string& message)
      : InvalidRating(std::vector<RatingIssue>{{pointer, message}}) {}
  std::vector<RatingIssue> issues;
};

}  // namespace gearsph::gear::iso6336
