"""The designer's studio: a Voila page over the library (make studio)."""
