# SPDX-License-Identifier: BSD-3-Clause
"""The `stickslip` command from the Python package: ``python -m stickslip ...``
and the console script ``stickslip`` that pip installs both run the compiled
command bundled with the module (stickslip/_bin/stickslip, built by setup.py),
with the same arguments, output and exit status (docs/guide.md).

Outside a pip install (PYTHONPATH=build/python), the environment variable
STICKSLIP_CLI may name the command to run instead.
"""
import os
import subprocess
import sys
from pathlib import Path


def command_path():
    """Path of the compiled `stickslip` command this package runs."""
    bundled = Path(__file__).resolve().parent / "_bin" / "stickslip"
    if bundled.is_file():
        return str(bundled)
    other = os.environ.get("STICKSLIP_CLI")
    if other:
        return other
    sys.exit("stickslip: this installation of the Python package has no bundled command "
             f"({bundled} is missing): install it with pip (docs/guide.md#installation-with-pip), "
             "or set STICKSLIP_CLI to the path of a built stickslip command")


def main(argv=None):
    """Run the command with argv (default: this process's arguments)."""
    args = sys.argv[1:] if argv is None else list(argv)
    exe = command_path()
    if os.name == "posix" and argv is None:
        # Replace this process: signals (Ctrl-C, SIGTERM and their checkpoints)
        # and the exit status then belong to the command itself.
        sys.stdout.flush()
        sys.stderr.flush()
        os.execv(exe, ["stickslip", *args])
    return subprocess.call([exe, *args])


if __name__ == "__main__":
    sys.exit(main())
