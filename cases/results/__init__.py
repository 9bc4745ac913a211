"""A run's results: history, summary, plots, pictures and VTK series."""
