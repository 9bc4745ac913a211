"""Scene files: TOML validated once into frozen dataclasses, with the checks and the tables they name."""
