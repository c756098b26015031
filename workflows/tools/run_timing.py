"""Running mppm's stages from a study and judging the machine while they run: a command's output or
a clear error, the run estimate's numbers (mppm-solve --estimate), the load average, and the CPU time
that other processes took during a block (from /proc/stat less this process's children), which
tells a run timed on an idle machine from one timed beside other work."""
import os
import re
import subprocess

from script_exit import RunError

CLOCK_TICKS = os.sysconf("SC_CLK_TCK") if hasattr(os, "sysconf") else 100


def run(command):
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        raise RunError(f"{' '.join(command)} failed ({result.returncode}): {result.stderr.strip()}")
    return result


def estimate_numbers(text):
    """(predicted wall seconds, predicted peak MiB) of mppm-solve --estimate's output."""
    wall = re.search(r"wall time\s+~([0-9.e+-]+) (s|min|h)", text)
    memory = re.search(r"peak memory\s+~([0-9.]+) (KiB|MiB|GiB)", text)
    if not wall or not memory:
        raise RunError(f"cannot read the estimate:\n{text}")
    seconds = float(wall.group(1)) * {"s": 1, "min": 60, "h": 3600}[wall.group(2)]
    mib = float(memory.group(1)) * {"KiB": 1 / 1024, "MiB": 1, "GiB": 1024}[memory.group(2)]
    return seconds, mib


def load_average():
    with open("/proc/loadavg") as f:
        return float(f.read().split()[0])


def busy_cpu_seconds():
    """CPU seconds every process has spent not idle since boot (all cores)."""
    with open("/proc/stat") as f:
        fields = [int(v) for v in f.readline().split()[1:]]
    idle = fields[3] + (fields[4] if len(fields) > 4 else 0)  # idle, iowait
    return (sum(fields[:8]) - idle) / CLOCK_TICKS


def children_cpu_seconds():
    t = os.times()
    return t.children_user + t.children_system


class OtherWork:
    """The CPU seconds other processes took while the block ran (this process's children excluded):
    with OtherWork() as w: ...; w.seconds, w.load_before, w.load_after."""

    def __enter__(self):
        self.load_before = load_average()
        self._busy, self._children = busy_cpu_seconds(), children_cpu_seconds()
        return self

    def __exit__(self, *exc):
        self.seconds = max(0.0, (busy_cpu_seconds() - self._busy) - (children_cpu_seconds() - self._children))
        self.load_after = load_average()
        return False
