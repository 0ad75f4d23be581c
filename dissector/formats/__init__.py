"""Capture file formats: each reader turns a byte stream into model.Chunk objects.

`dissector.sources.open_source` picks the reader from the content; the readers here only parse.
"""
