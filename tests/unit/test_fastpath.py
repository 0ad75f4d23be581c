"""The fast path must give exactly what the Construct grammar gives, or step aside."""
from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from dissector.decode.fastpath import fast_parse
from dissector.protocol.grammar import GrammarError, parse_pdu
from dissector.model import Kind
from strategies import transactions

FUNCTIONS = [1, 2, 3, 4, 5, 6, 7, 8, 11, 12, 15, 16, 17, 20, 21, 22, 23, 24, 43]


def grammar_result(function: int, kind: Kind, pdu: bytes):
    try:
        return parse_pdu(function, kind, pdu[1:])
    except GrammarError:
        return "error"


@settings(max_examples=400, deadline=None)
@given(transactions())
def test_same_container_for_valid_frames(transaction) -> None:
    request, response, _ = transaction
    for adu, kind in ((request, Kind.REQUEST), (response, Kind.RESPONSE)):
        pdu = adu[1:-2]
        function = pdu[0] & 0x7F
        if pdu[0] & 0x80:
            kind = Kind.EXCEPTION
        fast = fast_parse(function, kind, pdu)
        if fast is not None:
            assert fast == grammar_result(function, kind, pdu)


@settings(max_examples=1000, deadline=None)
@given(st.sampled_from(FUNCTIONS), st.sampled_from(list(Kind)[:3]), st.binary(max_size=40))
def test_arbitrary_bytes_agree_or_fall_back(function: int, kind: Kind, data: bytes) -> None:
    pdu = bytes([function | (0x80 if kind is Kind.EXCEPTION else 0)]) + data
    fast = fast_parse(function, kind, pdu)
    if fast is not None:
        assert fast == grammar_result(function, kind, pdu)


def test_fast_path_covers_the_polling_traffic() -> None:
    assert fast_parse(3, Kind.REQUEST, bytes.fromhex("0320d00003")) == {"start": 8400, "quantity": 3, "trailing": b""}
    assert fast_parse(3, Kind.RESPONSE, bytes.fromhex("0306800000030002"))["values"] == [0x8000, 3, 2]
    assert fast_parse(3, Kind.RESPONSE, bytes.fromhex("03058000000300")) is None  # odd count: grammar's job
