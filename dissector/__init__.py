"""vw3-dissector: a Wireshark-style dissector and frame analyzer for Modbus serial buses.

Stages, in the order data flows: sources (files, pcap, serial) -> framer -> pairing -> decode ->
annotator (device profiles) -> renderers. `dissector.pipeline.dissect` runs the middle of it.
"""

__version__ = "0.1.0"
