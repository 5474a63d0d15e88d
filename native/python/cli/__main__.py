"""``python -m geofair``: the command line (geofair_cli)."""

import sys

from geofair_cli import main

sys.exit(main())
