"""What the command-line end-to-end tests share: the tool under test (STRICTMIN_CLI, set by
ctest), the shared data folder, running the tool with an expected exit code, and writing a
small input file."""
import os
import subprocess

CLI = os.environ.get("STRICTMIN_CLI", "strictmin")
DATA = os.environ.get("STRICTMIN_SHARED_DATA", "")


def run(*args, check_code=None, cwd=None, timeout=300):
    """Runs `strictmin ARGS`; with check_code, fails unless it exits with that code."""
    p = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, timeout=timeout, cwd=cwd)
    if check_code is not None and p.returncode != check_code:
        raise AssertionError(f"exit {p.returncode} != {check_code}\nstdout: {p.stdout}\nstderr: {p.stderr[-3000:]}")
    return p


def write(path, text):
    with open(path, "w") as f:
        f.write(text)
    return path
