"""``python -m vlnverse_baselines``: the command line (see ``vlnverse_baselines.cli``)."""

from __future__ import annotations

import sys

from vlnverse_baselines.cli import main

sys.exit(main())
