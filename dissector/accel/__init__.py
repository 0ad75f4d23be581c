"""The compiled path (the _summary extension) and its Python glue.

The extension is checked once, here, before any caller imports it: built from other sources than the
ones beside it (stamp.py), it is taken out of the import system, so `from dissector.accel import
_summary` raises ImportError everywhere and the Python stages do everything.
"""
import sys

try:
    from dissector.accel import _summary
except ImportError:  # built without a C compiler
    pass
else:
    from dissector.accel.stamp import stamp as _stamp

    _expected = _stamp()
    if _expected is not None and getattr(_summary, "SOURCES", None) != _expected:
        sys.modules[f"{__name__}._summary"] = None  # type: ignore[assignment]
        del _summary
    del _stamp, _expected
