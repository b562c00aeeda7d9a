"""The bottom layer: errors, messages as data, gettext, wording, lazy numpy, the cache folder, the
backends' probes, the shipped resources. It imports nothing else of bras-kit."""
