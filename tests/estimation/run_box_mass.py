#!/usr/bin/env python3
"""box_mass on the MuJoCo plant (paper 1, Sec. V-A; docs/estimation.md), and mrqp-irls over its log.

mrqp-run tools/scenes/box_mass.yaml --plant mujoco: the run ends without a safe stop or an
allocation in the loop, the QP's model of the box starts from the estimation section's initial
mass and ends at the estimate (feed_back; the log's est_box_model_mass), and summary.json's estimate of
the box's mass lies within 1 % of the world's (the scene file's box mass, read here from the YAML)
and stays there (mass_converged_s not null). Then mrqp-irls over the run's log: without the prior,
the batch mass is within 1 % of the truth too; with the filter's prior as rows and Huber's
threshold out of reach, the batch is the Gaussian posterior that the filter (Q = 0) computes
recursively, so it must equal the online filter's final state (to 1e-6 of a standard deviation).

usage: run_box_mass.py MRQP_RUN MRQP_IRLS SCENE OUTDIR
"""
import json
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
import mrqp_run  # noqa: E402  (tests/support/mrqp_run.py)


def scene_box(scene):
    text = open(scene).read()
    mass = float(re.search(r"- name: box\n    model: rigid_object\n    mass: ([0-9.e-]+)", text).group(1))
    initial = float(re.search(r"initial: \{mass: ([0-9.e-]+)", text).group(1))
    return mass, initial


def main():
    run, irls, scene, out = sys.argv[1:5]
    true_mass, initial = scene_box(scene)
    r = mrqp_run.run(run, scene, out, plant="mujoco")
    failures = []
    if r.returncode != 0 or r.summary is None:
        print(r.stdout, r.stderr)
        print("FAIL: mrqp-run exit %d" % r.returncode)
        return 1
    s = r.summary
    print("mass: true %g, initial %g, estimate %g ± %g, converged after %s s, CoM error %s m"
          % (s["mass_true_kg"], s["mass_initial_kg"], s["mass_estimate_kg"], s["mass_std_kg"],
             s["mass_converged_s"], s["com_estimate_error_m"]))
    failures += r.failures()  # exit 0, no safe stop, no allocation in the loop
    if s["mass_true_kg"] != true_mass or s["mass_initial_kg"] != initial:
        failures.append("mass_true_kg / mass_initial_kg differ from the scene file's")
    if abs(s["mass_estimate_kg"] - true_mass) > 0.01 * true_mass:
        failures.append("mass estimate %g not within 1 %% of %g" % (s["mass_estimate_kg"], true_mass))
    if s["mass_converged_s"] is None:
        failures.append("mass_converged_s is null")
    if not isinstance(s["com_estimate_error_m"], float):
        failures.append("com_estimate_error_m missing")

    # feed_back: the QP's model of the box starts from the initial mass and ends at the estimate.
    rows = r.csv_rows("log.csv")
    if float(rows[0]["est_box_model_mass"]) != initial:
        failures.append("the QP's model does not start from the initial mass: %s" % rows[0]["est_box_model_mass"])
    if abs(float(rows[-1]["est_box_model_mass"]) - s["mass_estimate_kg"]) > 1e-6:
        failures.append("the QP's model mass %s is not the estimate" % rows[-1]["est_box_model_mass"])

    batch = subprocess.run([irls, out], capture_output=True, text=True)
    print(batch.stdout, batch.stderr)
    j = json.load(open(os.path.join(out, "irls.json")))["box"]
    if batch.returncode != 0 or j["parameters"][0] != "m":
        failures.append("mrqp-irls failed")
    elif abs(j["batch"][0] - true_mass) > 0.01 * true_mass:
        failures.append("batch mass %g not within 1 %%" % j["batch"][0])
    post = subprocess.run([irls, out, "--with-prior", "--huber-k", "1e9", "--json",
                           os.path.join(out, "irls_prior.json")], capture_output=True, text=True)
    jp = json.load(open(os.path.join(out, "irls_prior.json")))["box"]
    for k, name in enumerate(jp["parameters"]):
        d = abs(jp["batch"][k] - jp["online"][k])
        if post.returncode != 0 or not d <= 1e-6 * jp["online_std"][k]:
            failures.append("%s: batch with prior %r, online %r (σ %r)" % (name, jp["batch"][k], jp["online"][k],
                                                                         jp["online_std"][k]))
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
