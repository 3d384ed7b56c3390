#!/usr/bin/python3
"""PySPH's oscillating plate (examples/solid_mech/oscillating_plate.py, as
shipped by Debian's python3-pysph) with the transverse velocity Vf as an
option, the tip history written as CSV and, if the run is long enough, its
period against the thin-plate formula of validation.md section 5.

`gearsph bench` runs this script; it prints one JSON line last:
  {"particles": N, "steps": S, "run_s": T, "period_s": P | null,
   "reference_period_s": R, "period_error": e | null}
where run_s is PySPH's own "Run took" time (time loop, no setup or
compilation) so that both codes are timed on the same part of the work.
"""
import json
import math
import os
import sys

from pysph.examples.solid_mech.oscillating_plate import OscillatingPlate


class BenchPlate(OscillatingPlate):
    def add_user_options(self, group):
        group.add_argument("--vf", action="store", type=float, dest="vf", default=0.05,
                           help="edge velocity factor Vf (the example uses 0.05)")

    def consume_user_options(self):
        self.vf_option = self.options.vf

    def create_particles(self):
        # initialize() sets the example's Vf before the options are read.
        self.Vf = self.vf_option
        return super().create_particles()


def tip_history(app):
    from pysph.solver.utils import iter_output
    t, y = [], []
    for sd, array in iter_output(app.output_files, "plate"):
        t.append(sd["t"])
        y.append(array.y[array.amplitude_idx[0]])
    return t, y


def period_from_crossings(t, y):
    # Same estimator as solver/run/signal.cpp: 2 (last - first) / (count - 1)
    # over the sign changes of y about the initial (equilibrium) height.
    y0 = y[0]
    crossings = []
    for k in range(1, len(t)):
        a, b = y[k - 1] - y0, y[k] - y0
        if k > 1 and a * b < 0.0:
            crossings.append(t[k - 1] + (t[k] - t[k - 1]) * a / (a - b))
    if len(crossings) < 2:
        return None
    return 2.0 * (crossings[-1] - crossings[0]) / (len(crossings) - 1)


def main():
    app = BenchPlate()
    app.run()
    # Thin-plate reference, plane strain (validation.md section 5).
    E, nu, rho, H, L = 2e6, 0.3975, 1000.0, 0.02, 0.2
    k = 1.875 / L
    omega = math.sqrt(E * H * H * k ** 4 / (12.0 * rho * (1.0 - nu * nu)))
    ref = 2.0 * math.pi / omega
    t, y = tip_history(app)
    with open(os.path.join(app.output_dir, "tip.csv"), "w") as f:
        f.write("t_s,tip_y_m\n")
        for a, b in zip(t, y):
            f.write("%.9g,%.9g\n" % (a, b))
    period = period_from_crossings(t, y)
    run_s = None
    log = os.path.join(app.output_dir, os.path.basename(app.fname) + ".log")
    if os.path.exists(log):
        for line in open(log):
            if "Run took" in line:
                run_s = float(line.split("Run took:")[1].split()[0])
    n = sum(pa.get_number_of_particles() for pa in app.particles)
    steps = int(app.solver.count)
    print(json.dumps({"particles": n, "steps": steps, "run_s": run_s, "period_s": period,
                      "reference_period_s": ref,
                      "period_error": None if period is None else (period - ref) / ref}))
    sys.stdout.flush()


if __name__ == "__main__":
    main()
