"""Parameter sweeps on Dask: designs, variants, the sweep folder and its tables."""
