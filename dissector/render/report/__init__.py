"""`--report FILE`: one self-contained HTML page of a capture (see collect.py and html.py)."""
from dissector.render.report.collect import ReportCollector
from dissector.render.report.html import write_report

__all__ = ["ReportCollector", "write_report"]
