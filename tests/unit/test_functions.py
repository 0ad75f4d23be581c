"""One request/response pair per public function code, from the examples of the Modbus Application
Protocol Specification v1.1b3 (slave 1 added; CRC by the reference algorithm)."""
from __future__ import annotations

import pytest

from helpers import decode, rtu


def pair(request: str, response: str) -> tuple[dict, dict]:
    items = decode(rtu(request) + rtu(response))
    assert len(items) == 2, items
    assert items[1]["request_frame"] == 1
    assert all(item["crc_ok"] for item in items)
    return items[0], items[1]


def test_fc1_read_coils() -> None:
    request, response = pair("01 01 0013 0013", "01 01 03 CD 6B 05")
    assert (request["kind"], request["start"], request["quantity"]) == ("request", 19, 19)
    bits = [bit["value"] for bit in response["bits"]]
    # 0xCD = coils 27..20 = 1100 1101, LSB first
    assert bits[:8] == [1, 0, 1, 1, 0, 0, 1, 1]
    assert len(bits) == 19
    assert response["bits"][0]["address"] == 19 and response["bits"][-1]["address"] == 37
    assert bits[16:] == [1, 0, 1]
    assert response["warnings"] == []


def test_fc2_read_discrete_inputs() -> None:
    request, response = pair("01 02 00C4 0016", "01 02 03 AC DB 35")
    assert (request["start"], request["quantity"]) == (196, 22)
    assert len(response["bits"]) == 22
    assert [bit["value"] for bit in response["bits"][:8]] == [0, 0, 1, 1, 0, 1, 0, 1]


def test_fc3_read_holding_registers() -> None:
    request, response = pair("01 03 006B 0003", "01 03 06 022B 0000 0064")
    assert request["raw"] == "0103006b00037417"
    assert response["registers"] == [
        {"address": 107, "value": 555},
        {"address": 108, "value": 0},
        {"address": 109, "value": 100},
    ]


def test_fc4_read_input_registers() -> None:
    _, response = pair("01 04 0008 0001", "01 04 02 000A")
    assert response["registers"] == [{"address": 8, "value": 10}]


def test_fc5_write_single_coil_echo_is_a_response() -> None:
    request, response = pair("01 05 00AC FF00", "01 05 00AC FF00")
    assert request["kind"] == "request" and response["kind"] == "response"
    assert response["bits"] == [{"address": 172, "value": 1}]


def test_fc6_write_single_register_echo_is_a_response() -> None:
    request, response = pair("01 06 0001 0003", "01 06 0001 0003")
    assert (request["kind"], response["kind"]) == ("request", "response")
    assert request["registers"] == response["registers"] == [{"address": 1, "value": 3}]


def test_fc7_read_exception_status() -> None:
    request, response = pair("01 07", "01 07 6D")
    assert request["length"] == 4 and response["length"] == 5
    assert response["fields"] == {"status": 0x6D}


def test_fc8_diagnostics_echo() -> None:
    request, response = pair("01 08 0000 A537", "01 08 0000 A537")
    assert request["subfunction"] == 0 and response["subfunction"] == 0
    assert request["subfunction_name"] == "Return Query Data"
    assert response["fields"]["data"] == "a537"


def test_fc8_counter() -> None:
    request, response = pair("01 08 000B 0000", "01 08 000B 0123")
    assert response["subfunction_name"] == "Return Bus Message Count"
    assert response["fields"]["data"] == "0123"


def test_fc11_comm_event_counter() -> None:
    _, response = pair("01 0B", "01 0B FFFF 0108")
    assert response["fields"] == {"status": 0xFFFF, "event_count": 264}


def test_fc12_comm_event_log() -> None:
    _, response = pair("01 0C", "01 0C 08 0000 0108 0121 20 00")
    assert response["fields"] == {
        "byte_count": 8,
        "status": 0,
        "event_count": 264,
        "message_count": 289,
        "events": "2000",
        "event_list": [{"byte": 0x20, "event": "Unknown Event"}, {"byte": 0, "event": "Initiated Communication Restart"}],
    }


def test_fc15_write_multiple_coils() -> None:
    request, response = pair("01 0F 0013 000A 02 CD 01", "01 0F 0013 000A")
    assert (request["start"], request["quantity"]) == (19, 10)
    assert [bit["value"] for bit in request["bits"]] == [1, 0, 1, 1, 0, 0, 1, 1, 1, 0]
    assert (response["kind"], response["start"], response["quantity"]) == ("response", 19, 10)


def test_fc16_write_multiple_registers() -> None:
    request, response = pair("01 10 0001 0002 04 000A 0102", "01 10 0001 0002")
    assert request["registers"] == [{"address": 1, "value": 10}, {"address": 2, "value": 258}]
    assert (response["kind"], response["start"], response["quantity"]) == ("response", 1, 2)


def test_fc17_report_server_id() -> None:
    _, response = pair("01 11", "01 11 03 0A FF 01")
    # server id 0x0A, run indicator ON, one byte of device data (not printable: hex)
    assert response["fields"] == {"byte_count": 3, "server_id": 10, "run_indicator": "ON", "additional_data": "01"}
    assert response["warnings"] == []


def test_fc20_read_file_record() -> None:
    request, response = pair(
        "01 14 0E 06 0004 0001 0002 06 0003 0009 0002", "01 14 0C 05 06 0DFE 0020 05 06 33CD 0040"
    )
    assert request["fields"]["subrequests"] == [
        {"reference_type": 6, "file": 4, "record": 1, "length": 2},
        {"reference_type": 6, "file": 3, "record": 9, "length": 2},
    ]
    assert response["fields"]["subresponses"] == [
        {"length": 5, "reference_type": 6, "values": [0x0DFE, 0x0020]},
        {"length": 5, "reference_type": 6, "values": [0x33CD, 0x0040]},
    ]


def test_fc21_write_file_record_echo() -> None:
    request, response = pair("01 15 0D 06 0004 0007 0003 06AF 04BE 100D", "01 15 0D 06 0004 0007 0003 06AF 04BE 100D")
    assert (request["kind"], response["kind"]) == ("request", "response")
    assert request["fields"]["records"] == [
        {"reference_type": 6, "file": 4, "record": 7, "length": 3, "values": [0x06AF, 0x04BE, 0x100D]}
    ]


def test_fc22_mask_write_register() -> None:
    request, response = pair("01 16 0004 00F2 0025", "01 16 0004 00F2 0025")
    assert request["fields"] == {"address": 4, "and_mask": 0xF2, "or_mask": 0x25}
    assert response["kind"] == "response"


def test_fc23_read_write_multiple_registers() -> None:
    request, response = pair(
        "01 17 0003 0006 000E 0003 06 00FF 00FF 00FF", "01 17 0C 00FE 0ACD 0001 0003 000D 00FF"
    )
    assert (request["start"], request["quantity"]) == (3, 6)
    assert request["registers"] == [{"address": 14 + i, "value": 255} for i in range(3)]
    assert [r["address"] for r in response["registers"]] == [3, 4, 5, 6, 7, 8]
    assert [r["value"] for r in response["registers"]] == [0xFE, 0x0ACD, 1, 3, 0x0D, 0xFF]


def test_fc24_read_fifo_queue() -> None:
    request, response = pair("01 18 04DE", "01 18 0006 0002 01B8 1284")
    assert request["start"] == 1246
    assert response["fields"] == {"byte_count": 6, "fifo_count": 2, "values": [0x01B8, 0x1284]}


def test_fc43_mei13_and_unknown_function_are_framed_by_crc() -> None:
    items = decode(rtu("01 2B 0D 00 01 02 03") + rtu("01 64 01 02 03 04 05") + rtu("01 03 0000 0001"))
    assert [item["length"] for item in items] == [9, 9, 8]
    assert items[0]["fields"] == {"mei_type": 13, "mei_type_name": "CANopen General Reference",
                                   "body": {"data": "00010203"}}
    assert items[1]["function_name"] == "User-defined function 100"
    assert items[1]["fields"] == {"data": "0102030405"}


@pytest.mark.parametrize("code,name", [(1, "Illegal Function"), (2, "Illegal Data Address"), (4, "Server Device Failure"), (11, "Gateway Target Device Failed to Respond")])
def test_exception_names(code: int, name: str) -> None:
    items = decode(rtu("01 01 0013 0013") + rtu(f"01 81 {code:02X}"))
    assert items[1]["kind"] == "exception"
    assert (items[1]["exception_code"], items[1]["exception_name"]) == (code, name)
    assert items[1]["function"] == 1


def test_unknown_exception_code_is_flagged_and_decoded() -> None:
    """The card manual's own exception example carries code 00."""
    (item,) = decode(rtu("01 83 00"))
    assert item["kind"] == "exception" and item["exception_code"] == 0
    assert item["exception_name"] == "Unknown exception 0"
    assert item["warnings"] == ["exception code 0 is not defined by the spec"]


@pytest.mark.parametrize(
    "request_hex,warning",
    [
        ("01 03 0000 0000", "quantity 0 outside the spec's 1..125"),
        ("01 03 0000 007E", "quantity 126 outside the spec's 1..125"),
        ("01 01 0000 07D1", "quantity 2001 outside the spec's 1..2000"),
        ("01 10 0001 0002 02 000A", "byte count 2 disagrees with the quantity 2"),
        ("01 03 FFFF 0002", "addresses 65535..65536 run past 65535"),
    ],
)
def test_spec_limits_are_warnings(request_hex: str, warning: str) -> None:
    items = decode(rtu(request_hex))
    assert warning in items[0]["warnings"]


def test_response_byte_count_disagreeing_with_request() -> None:
    items = decode(rtu("01 03 0000 0003") + rtu("01 03 04 0001 0002"))
    assert items[1]["warnings"] == ["byte count 4 disagrees with the registers asked (3)"]
    assert [r["address"] for r in items[1]["registers"]] == [0, 1]


def test_broadcast_write_gets_no_response_and_read_broadcast_is_flagged() -> None:
    items = decode(rtu("00 06 2329 000A") + rtu("01 03 0000 0001") + rtu("01 03 02 0007") + rtu("00 03 0000 0001"))
    assert items[0]["broadcast"] is True and items[0]["unanswered"] is False
    assert items[2]["request_frame"] == 2
    assert "Read Holding Registers cannot be broadcast (slave 0)" in items[3]["warnings"]


def test_request_followed_by_request_is_unanswered() -> None:
    items = decode(rtu("01 03 0000 0001") + rtu("02 03 0000 0001") + rtu("02 03 02 0007"))
    assert items[0]["unanswered"] is True
    assert items[1]["unanswered"] is False and items[1]["response_frame"] == 3
