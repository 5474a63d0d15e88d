"""A benchmark's solves, each in a child process of its own (bench/realmesh.py, bench/holes.py).

A crash, hang or runaway allocation of one solve then costs that case alone. The benchmark
runs itself as the child (``--child``); the child times the call with ``solve``, writes its
arrays to a file and prints one JSON line with ``report``; the parent starts it with
``run``, which returns that line as a dict.
"""

import json
import subprocess
import time

import numpy as np

IMPORT_RETRIES, IMPORT_WAIT = 40, 15  # geofair may be rebuilt while a benchmark runs: wait for it

# numpy's OpenBLAS starts its threads at ``import numpy``, and they spin for about 0.1 s on
# the second core that geofair's solves use; in Blender numpy was imported at startup.
SETTLE_SECONDS = 0.3


def settle(seconds=SETTLE_SECONDS):
    """Waits ``seconds`` (negative: none) after a child's imports and input, before its timed
    call: numpy's BLAS threads are asleep then, as in Blender (``SETTLE_SECONDS``)."""
    time.sleep(max(0.0, seconds))


def scalar(x):
    """``x`` as JSON can hold it: numpy scalars as Python ones, sequences element-wise, the
    rest (an enum, say) as its ``str``; None stays None."""
    if isinstance(x, (bool, np.bool_)):
        return bool(x)
    if isinstance(x, (int, np.integer)):
        return int(x)
    if isinstance(x, (float, np.floating)):
        return float(x)
    if isinstance(x, (list, tuple)):
        return [scalar(y) for y in x]
    return None if x is None else str(x)


def solve(call):
    """Runs ``call()`` after ``settle()`` and times it: ``(report, result)``.

    ``report["status"]`` is "done" with the call's wall time in "seconds", or, with no
    result, "invalid" (a ValueError: the library refused the input) or "error" (anything
    else, geofair.SolverError among them) with the error in "message".
    """
    settle()
    t = time.perf_counter()
    try:
        result = call()
    except ValueError as error:
        return {"status": "invalid", "message": str(error), "seconds": time.perf_counter() - t}, None
    except Exception as error:  # geofair.SolverError (a RuntimeError) and anything else
        message = f"{type(error).__name__}: {error}"
        return {"status": "error", "message": message, "seconds": time.perf_counter() - t}, None
    return {"status": "done", "seconds": time.perf_counter() - t}, result


def report(out):
    """Prints the child's report as the one JSON line ``run`` reads."""
    print(json.dumps(out), flush=True)


def _import_failed(stderr):
    last = stderr.strip().splitlines()[-1:] or [""]
    return last[0].startswith(("ImportError", "ModuleNotFoundError"))


def run(cmd, timeout):
    """Runs the child command ``cmd`` (a list): its report (the last line it printed) as a
    dict, or ``{"status": "timeout", "seconds": timeout}`` when it ran longer than
    ``timeout`` seconds, or ``{"status": "error", "message": ...}`` (the last line of its
    stderr) when it exited without a report. A child that could not import geofair (the
    module being rebuilt) is started again after a wait, up to IMPORT_RETRIES times."""
    for _ in range(IMPORT_RETRIES):
        try:
            process = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
        except subprocess.TimeoutExpired:
            return {"status": "timeout", "seconds": timeout}
        if not _import_failed(process.stderr):
            break
        print(f"# geofair not importable (being rebuilt?), retrying in {IMPORT_WAIT} s", flush=True)
        time.sleep(IMPORT_WAIT)
    lines = process.stdout.strip().splitlines()
    if process.returncode != 0 or not lines:
        err = process.stderr.strip().splitlines()
        return {"status": "error", "message": err[-1] if err else f"exit status {process.returncode}"}
    return json.loads(lines[-1])
