"""The applications over the library: the command line and the batch."""
