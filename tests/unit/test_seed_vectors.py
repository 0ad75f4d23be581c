"""Every frame printed in the seed pages and the reference, decoded to the documented fields."""
from __future__ import annotations

from dissector.protocol.crc import crc16, crc16_reference, lrc
from helpers import decode, hx
from seed_frames import DEVICE_ID_REQUEST, DEVICE_ID_RESPONSE, SCENARIO_1, SCENARIO_2, SCENARIO_3, SCENARIO_REQUEST

def test_check_vectors() -> None:
    assert crc16_reference(hx("01 03 00 6B 00 03")) == 0x1774
    assert crc16(hx("01 03 00 6B 00 03")) == 0x1774
    assert lrc(hx("01 06 04 05 12 34")) == 0xAA


def test_p38_request() -> None:
    (request,) = decode(SCENARIO_REQUEST)
    assert request["kind"] == "request"
    assert request["slave"] == 12
    assert request["function"] == 3
    assert request["function_name"] == "Read Holding Registers"
    assert (request["start"], request["quantity"]) == (8400, 3)
    assert request["crc_ok"] is True
    assert request["crc"] == 0xEF0E == request["crc_expected"]
    assert request["raw"] == "0c0320d000030eef"


def test_p38_scenarios_in_one_capture() -> None:
    stream = SCENARIO_REQUEST + SCENARIO_1 + SCENARIO_REQUEST + SCENARIO_2 + SCENARIO_REQUEST + SCENARIO_3
    items = decode(stream)
    assert [item["kind"] for item in items] == ["request", "response"] * 2 + ["request", "exception"]
    assert [item["frame"] for item in items] == [1, 2, 3, 4, 5, 6]
    assert [item["offset"] for item in items] == [0, 8, 19, 27, 38, 46]
    assert sum(item["length"] for item in items) == len(stream)
    first, second = items[1], items[3]
    assert first["registers"] == [
        {"address": 8400, "value": 0x8000},
        {"address": 8401, "value": 3},
        {"address": 8402, "value": 2},
    ]
    assert second["registers"] == [
        {"address": 8400, "value": 0x8000},
        {"address": 8401, "value": 0x8000},
        {"address": 8402, "value": 2},
    ]
    assert first["request_frame"] == 1 and second["request_frame"] == 3
    exception = items[5]
    assert exception["exception_code"] == 2
    assert exception["exception_name"] == "Illegal Data Address"
    assert exception["function"] == 3
    assert exception["request_frame"] == 5
    assert all(item["crc_ok"] for item in items)
    assert all(item["warnings"] == [] for item in items)


def test_p32_device_identification() -> None:
    assert len(DEVICE_ID_RESPONSE) == 55
    request, response = decode(DEVICE_ID_REQUEST + DEVICE_ID_RESPONSE)
    assert request["kind"] == "request"
    assert request["function"] == 43
    assert request["fields"] == {"mei_type": 14, "mei_type_name": "Read Device Identification",
                                 "body": {"read_code": 1, "read_code_name": "basic", "object_id": 0}}
    assert response["kind"] == "response"
    assert response["length"] == 55
    assert response["crc_ok"] is True
    assert response["request_frame"] == 1
    assert response["objects"] == [
        {"id": 0, "name": "VendorName", "value": "Telemecanique"},
        {"id": 1, "name": "ProductCode", "value": "ATV71HU15M3"},
        {"id": 2, "name": "MajorMinorRevision", "value": "0201"},
        {"id": 6, "name": "UserApplicationName", "value": "MACHINE 4"},
    ]
    body = response["fields"]["body"]
    assert (body["conformity"], body["more_follows"], body["next_object_id"], body["object_count"]) == (
        2,
        0,
        0,
        4,
    )


def test_worked_fc3_example() -> None:
    request, response = decode(hx("02 03 0C 1E 00 04 27 6C 02 03 08 00 28 02 58 01 F4 00 00 52 B0"))
    assert (request["start"], request["quantity"]) == (3102, 4)
    assert response["registers"] == [
        {"address": 3102, "value": 40},
        {"address": 3103, "value": 600},
        {"address": 3104, "value": 500},
        {"address": 3105, "value": 0},
    ]


def test_crc_only_trap_is_avoided() -> None:
    """The 6-byte prefix of the response has a valid CRC too; length rules must win."""
    request, response = decode(hx("01 04 00 00 00 01 31 CA 01 04 02 03 01 78 00"))
    assert request["kind"] == "request" and request["length"] == 8
    assert response["kind"] == "response" and response["length"] == 7
    assert response["registers"] == [{"address": 0, "value": 0x0301}]
    assert response["crc_ok"] is True
