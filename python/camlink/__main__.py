"""`python -m camlink` runs the command-line interface."""

import sys

from camlink.cli import main

sys.exit(main())
