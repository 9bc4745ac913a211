"""Running a model: the integration and its reduction to a history and a summary; the case library."""
