"""The outputs of one run of a case with several runs: OUT/RUN/ holds points.vtp (its copy of the
case's points file), run/ (mppm-solve) and post/ (mppm-postprocess). Shared by the case folders'
scripts (crack-branching, kalthoff-winkler)."""
import os

import mppm_outputs


def summary(out, run):
    return mppm_outputs.summary(os.path.join(out, run, "post"))


def energy_rows(out, run):
    return mppm_outputs.energy_rows(os.path.join(out, run, "run"))


def load_rows(out, run):
    return mppm_outputs.load_rows(os.path.join(out, run, "run"))


def run_info(out, run):
    return mppm_outputs.run_info(os.path.join(out, run, "run"))


def frames(out, run):
    """(time, path) of every frame of the run's ParaView series, in time order."""
    return mppm_outputs.frames(os.path.join(out, run, "post"))
