"""Results out: the result-file contract, SVG, PNG, PDF and JSON writers, plots."""
