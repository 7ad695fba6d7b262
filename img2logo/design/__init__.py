"""Design exploration (paper Sec. 7): edits of a level, regions and fills."""
