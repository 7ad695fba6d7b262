"""The batch: a folder of images to logos, in worker processes, with a report and a gallery."""
