"""`python -m camlink` runs the command-line interface."""

from camlink.cli import run

run()
