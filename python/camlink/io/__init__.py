"""Files: results written and read back (Parquet, CSV and its sidecar), and
the course engine's model files (`.adm`/`.acf`) converted to camlink's.

Layer: above the base modules (errors, warnings, records, units, settings),
below the model API (`camlink.model`, `camlink.results`), which writes and
reads its files through it.
"""

#: Nothing is imported from the package itself: its modules are its API.
__all__: list[str] = []
