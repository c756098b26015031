#!/usr/bin/python3
"""Runs the LAMMPS PERI inputs of a benchmark (the 2-D plate of make_plate_input.py or the 3-D block
of make_block_input.py) at 1 and 2 MPI ranks and appends benchmark rows to a CSV.

Owns: launching Debian's `lmp` under `mpirun` (the Debian build has no OPENMP package, so
LAMMPS parallelizes with MPI ranks only), per-rank peak memory (GNU time around each rank,
summed), parsing LAMMPS's log (loop time, bond count, atoms, steps, damage), the checks that
LAMMPS ran the same problem the generator described, and the CSV rows
  case,effects,threads,points,bonds,steps,wall_seconds,bond_updates_per_second,peak_memory_bytes
where threads = MPI ranks, wall_seconds = LAMMPS's "Loop time" (the time loop only, set-up
excluded) and bond_updates_per_second = bonds * steps / wall_seconds. Standard library only.

Exit codes: 0 success; 2 bad input (missing inputs, bad option, bad CSV header);
1 LAMMPS failed or ran a different problem than the generator described.
"""

import argparse
import json
import os
import re
import shlex
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from mppm_outputs import write_text  # noqa: E402
from script_exit import InputError, RunError, run_main  # noqa: E402

CSV_HEADER = ("case,effects,threads,points,bonds,steps,wall_seconds,"
              "bond_updates_per_second,peak_memory_bytes,wall_seconds_max,repeats")


def parse_arguments(argv):
    parser = argparse.ArgumentParser(
        description="Run the LAMMPS peri/lps and peri/pmb benchmark inputs and append CSV rows.")
    parser.add_argument("csv", help="CSV file to append rows to (created with a header if missing)")
    parser.add_argument("--inputs", required=True,
                        help="directory written by the generator (holds BENCHMARK.json)")
    parser.add_argument("--benchmark", default="plate", choices=("plate", "block"),
                        help="plate (make_plate_input.py, default) or block (make_block_input.py)")
    parser.add_argument("--models", default="lps,pmb", help="subset of lps,pmb (default both)")
    parser.add_argument("--ranks", default="1,2", help="MPI rank counts (default 1,2)")
    parser.add_argument("--repeats", type=int, default=1,
                        help="runs of each model and rank count, the rank counts taking turns; the "
                             "row keeps the fastest loop and the slowest beside it (default 1)")
    parser.add_argument("--lmp", default="lmp", help="LAMMPS executable (default lmp)")
    parser.add_argument("--mpirun", default="mpirun", help="MPI launcher (default mpirun)")
    parser.add_argument("--mpirun-args", default="",
                        help="extra launcher arguments, e.g. '--bind-to none'")
    parser.add_argument("--log-dir", help="where LAMMPS logs go (default: --inputs)")
    args = parser.parse_args(argv)
    args.models = [m.strip() for m in args.models.split(",") if m.strip()]
    message = f"--ranks: expected comma-separated positive integers (got {args.ranks!r})"
    try:
        args.ranks = [int(r) for r in args.ranks.split(",") if r.strip()]
    except ValueError:
        raise InputError(message)
    if not args.ranks or min(args.ranks) < 1:
        raise InputError(message)
    return args


def load_plate(inputs, models, benchmark="plate"):
    path = os.path.join(inputs, f"{benchmark}.json")
    try:
        with open(path) as stream:
            plate = json.load(stream)
    except FileNotFoundError:
        raise InputError(f"{path}: not found (run make_{benchmark}_input.py --out-dir {inputs} first)")
    except (OSError, json.JSONDecodeError) as error:
        raise InputError(f"{path}: unreadable ({error})")
    for key in ("points", "bonds", "steps", "models"):
        if key not in plate:
            raise InputError(f"{path}: missing key '{key}' (expected the generator's output)")
    for model in models:
        if model not in plate["models"]:
            raise InputError(f"{path}: models: no '{model}' input (have "
                             f"{', '.join(sorted(plate['models'])) or 'none'}; expected lps/pmb)")
        input_path = os.path.join(inputs, plate["models"][model]["input"])
        if not os.path.isfile(input_path):
            raise InputError(f"{input_path}: not found (listed in {path})")
    return plate


def require_tools(args):
    for tool in (args.lmp, args.mpirun, "/usr/bin/time"):
        if shutil.which(tool) is None:
            raise InputError(f"{tool}: not found (install Debian packages lammps, openmpi-bin and time)")


def is_open_mpi(mpirun):
    try:
        text = subprocess.run([mpirun, "--version"], capture_output=True, text=True,
                              timeout=60).stdout
    except (OSError, subprocess.TimeoutExpired):
        return False
    return "Open MPI" in text or "OpenRTE" in text


def launcher(args, ranks, open_mpi):
    command = [args.mpirun]
    if open_mpi:
        if os.geteuid() == 0:
            command.append("--allow-run-as-root")  # containers often run as root
        if ranks > (os.cpu_count() or 1):
            command.append("--oversubscribe")
    command += shlex.split(args.mpirun_args)
    command += ["-np", str(ranks)]
    return command


def parse_log(text):
    """Numbers LAMMPS prints for the measured (last) run; None where a line is missing.

    The input does a set-up `run 0` first, so the loop time and thermo rows are taken from the
    last run block."""
    def find(pattern, convert=float):
        match = re.search(pattern, text, re.MULTILINE)
        return convert(match.group(1)) if match else None

    loops = re.findall(r"^Loop time of (\S+) on (\d+) procs for (\d+) steps with (\d+) atoms",
                       text, re.MULTILINE)
    loop = loops[-1] if loops else None
    thermo = []
    header = text.rfind("\nStep KinEng")
    if header >= 0:
        for line in text[header + 1:].splitlines()[1:]:
            fields = line.split()
            if len(fields) != 5:
                break
            try:
                thermo.append(tuple(float(v) for v in fields))
            except ValueError:
                break
    memory = re.findall(r"Per MPI rank memory allocation \(min/avg/max\) = (\S+) \| (\S+) \| (\S+)",
                        text)
    cpu_use = re.findall(r"^(\S+)% CPU use with", text, re.MULTILINE)
    return {
        "cpu_use_percent": float(cpu_use[-1]) if cpu_use else None,
        "loop_seconds": float(loop[0]) if loop else None,
        "procs": int(loop[1]) if loop else None,
        "steps": int(loop[2]) if loop else None,
        "atoms": int(loop[3]) if loop else None,
        "created_atoms": find(r"^\s*Created (\d+) atoms", int),
        "bonds": find(r"total # of bonds = (\d+)", int),
        "thermo": thermo,
        "lammps_memory_mbytes_max": float(memory[-1][2]) if memory else None,
    }


def run_one(args, plate, model, ranks, open_mpi, log_dir):
    entry = plate["models"][model]
    input_path = os.path.abspath(os.path.join(args.inputs, entry["input"]))
    tag = f"{entry['case']}-{ranks}"
    log_path = os.path.join(log_dir, f"log.{tag}")
    rss_prefix = os.path.join(log_dir, f".rss.{tag}")
    # GNU time around each rank (not around mpirun, whose rusage reports only the largest
    # child), so the peak memory is summed over ranks.
    per_rank = ('exec /usr/bin/time -f %M -o "$0.${OMPI_COMM_WORLD_RANK:-${PMI_RANK:-0}}" "$@"')
    command = launcher(args, ranks, open_mpi) + [
        "sh", "-c", per_rank, rss_prefix,
        args.lmp, "-in", input_path, "-log", log_path, "-screen", "none", "-nocite"]
    for stale in [f"{rss_prefix}.{r}" for r in range(ranks)] + [log_path]:
        if os.path.exists(stale):
            os.unlink(stale)
    environment = dict(os.environ, OMP_NUM_THREADS="1")
    print(f"[lammps] {tag}: {' '.join(shlex.quote(c) for c in command)}", flush=True)
    started = time.monotonic()
    result = subprocess.run(command, capture_output=True, text=True, env=environment,
                            cwd=log_dir)
    elapsed = time.monotonic() - started
    log_text = open(log_path).read() if os.path.exists(log_path) else ""
    if result.returncode != 0:
        tail = "\n".join((log_text or result.stdout + result.stderr).splitlines()[-20:])
        raise RunError(f"{tag}: LAMMPS exited with code {result.returncode}; last lines:\n{tail}")

    found = parse_log(log_text)
    problems = []
    if found["loop_seconds"] is None or found["loop_seconds"] <= 0.0:
        problems.append("no positive 'Loop time' line")
    if found["procs"] != ranks:
        problems.append(f"ran on {found['procs']} procs, asked for {ranks}")
    if found["steps"] != plate["steps"]:
        problems.append(f"ran {found['steps']} steps, input asks for {plate['steps']}")
    if found["created_atoms"] != plate["points"] or found["atoms"] != plate["points"]:
        problems.append(f"created {found['created_atoms']} atoms and ended with {found['atoms']}, "
                        f"generator counted {plate['points']} points")
    if found["bonds"] != plate["bonds"]:
        problems.append(f"LAMMPS built {found['bonds']} bonds, generator counted {plate['bonds']}: "
                        "the families differ")
    if not found["thermo"] or found["thermo"][-1][0] != plate["steps"]:
        problems.append("no thermo line for the last step")
    elif found["thermo"][-1][4] != 0.0:
        problems.append(f"bonds broke (max damage {found['thermo'][-1][4]}): s00 is too small")
    rss_kilobytes = []
    for rank in range(ranks):
        try:
            with open(f"{rss_prefix}.{rank}") as stream:
                rss_kilobytes.append(int(stream.read().split()[-1]))
            os.unlink(f"{rss_prefix}.{rank}")
        except (OSError, ValueError, IndexError):
            problems.append(f"no peak memory from rank {rank} (is /usr/bin/time installed?)")
    if problems:
        raise RunError(f"{tag}: {'; '.join(problems)} (log: {log_path})")

    loop_seconds = found["loop_seconds"]
    rate = plate["bonds"] * plate["steps"] / loop_seconds
    peak_bytes = 1024 * sum(rss_kilobytes)
    print(f"[lammps] {tag}: loop {loop_seconds:.3f} s (process {elapsed:.1f} s), "
          f"{rate:.3e} bond updates/s, peak RSS {peak_bytes / 2**20:.1f} MiB over {ranks} rank(s) "
          f"(LAMMPS's own estimate {found['lammps_memory_mbytes_max']} MB per rank), "
          f"CPU use {found['cpu_use_percent']}% per rank", flush=True)
    # LAMMPS's "CPU use" is each rank's CPU time over the loop's wall time: well below 100 %
    # means other processes shared the cores and the rate above understates LAMMPS.
    if found["cpu_use_percent"] is not None and found["cpu_use_percent"] < 90.0:
        print(f"[lammps] {tag}: WARNING: LAMMPS got only {found['cpu_use_percent']}% of a core per "
              f"rank; the machine was busy and this rate is depressed", flush=True)
    return [entry["case"], entry["effects"], str(ranks), str(plate["points"]), str(plate["bonds"]),
            str(plate["steps"]), f"{loop_seconds:.6g}", f"{rate:.6g}", str(peak_bytes)]


def fastest_row(done):
    """The row of the fastest of `done` (run_one's rows of one model and rank count), with the
    slowest loop and the number of runs beside it."""
    fastest = min(done, key=lambda r: float(r[6]))
    slowest = max(float(r[6]) for r in done)
    return fastest + [f"{slowest:.6g}", str(len(done))]


def append_rows(csv_path, rows):
    """Existing rows + new rows written to a temporary file, then renamed: never half-written."""
    existing = ""
    if os.path.exists(csv_path):
        with open(csv_path) as stream:
            existing = stream.read()
        if existing and existing.splitlines()[0].strip() != CSV_HEADER:
            raise InputError(f"{csv_path}: first line is not the header '{CSV_HEADER}'")
        if existing and not existing.endswith("\n"):
            existing += "\n"
    text = existing or CSV_HEADER + "\n"
    text += "".join(",".join(row) + "\n" for row in rows)
    os.makedirs(os.path.dirname(os.path.abspath(csv_path)), exist_ok=True)
    write_text(csv_path, text)


def main(argv):
    try:
        args = parse_arguments(argv)
        if args.repeats < 1:
            raise InputError("--repeats: expected a positive integer")
        unknown = [m for m in args.models if m not in ("lps", "pmb")]
        if not args.models or unknown:
            raise InputError(f"--models: unknown model(s) {unknown or args.models} "
                             "(expected lps and/or pmb)")
        plate = load_plate(args.inputs, args.models, args.benchmark)
        require_tools(args)
        if os.path.exists(args.csv) and os.path.getsize(args.csv) > 0:
            with open(args.csv) as stream:
                if stream.readline().strip() != CSV_HEADER:
                    raise InputError(f"{args.csv}: first line is not the header '{CSV_HEADER}'")
        log_dir = os.path.abspath(args.log_dir or args.inputs)
        os.makedirs(log_dir, exist_ok=True)
    except InputError as error:
        print(f"run_lammps.py: {error}", file=sys.stderr)
        return 2
    except OSError as error:
        print(f"run_lammps.py: {error}", file=sys.stderr)
        return 2

    open_mpi = is_open_mpi(args.mpirun)
    load = os.getloadavg()
    print(f"[lammps] load average before the runs: {load[0]:.2f} {load[1]:.2f} {load[2]:.2f} "
          f"on {os.cpu_count()} CPUs", flush=True)
    rows = []
    try:
        # This VM's speed drifts by 10-30 % over minutes: the rank counts of a model take turns,
        # and the fastest of the repeats is the one least slowed by the machine.
        for model in args.models:
            runs = {ranks: [] for ranks in args.ranks}
            for _ in range(args.repeats):
                for ranks in args.ranks:
                    runs[ranks].append(run_one(args, plate, model, ranks, open_mpi, log_dir))
            for ranks in args.ranks:
                rows.append(fastest_row(runs[ranks]))
    except RunError as error:
        print(f"run_lammps.py: {error}", file=sys.stderr)
        return 1
    try:
        append_rows(args.csv, rows)
    except InputError as error:
        print(f"run_lammps.py: {error}", file=sys.stderr)
        return 2
    load = os.getloadavg()
    print(f"[lammps] load average after the runs: {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}; "
          f"{len(rows)} row(s) appended to {args.csv}", flush=True)
    return 0


if __name__ == "__main__":
    run_main(main)
