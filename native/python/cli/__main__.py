"""``python -m geofair``: the command line (geofair_cli)."""

import sys

import geofair_cli

if __name__ == "__main__":  # not on import (mypy's stubtest imports every submodule)
    sys.exit(geofair_cli.main())
