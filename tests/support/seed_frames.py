"""Frames printed in the seed pages (../shared/seeds), shared by the tests that use them."""
from __future__ import annotations

from helpers import hx

SCENARIO_REQUEST = hx("0C 03 20 D0 00 03 0E EF")
SCENARIO_1 = hx("0C 03 06 80 00 00 03 00 02 17 E4")
SCENARIO_2 = hx("0C 03 06 80 00 80 00 00 02 CE 24")
SCENARIO_3 = hx("0C 83 02 51 32")

DEVICE_ID_REQUEST = hx("02 2B 0E 01 00 34 77")
DEVICE_ID_RESPONSE = (
    hx("02 2B 0E 01 02 00 00 04")
    + hx("00 0D")
    + b"Telemecanique"
    + hx("01 0B")
    + b"ATV71HU15M3"
    + hx("02 04")
    + b"0201"
    + hx("06 09")
    + b"MACHINE 4"
    + hx("6F 50")
)
