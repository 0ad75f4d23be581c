"""Runs written from cached pieces (render/runs.py) give the texts an f-string per item gives."""
from __future__ import annotations

from hypothesis import given
from hypothesis import strategies as st

from dissector.model import BitList, RegisterList
from dissector.render.detail_plain import detail_text
from dissector.render.runs import AddressPieces, BitRuns, Pieces, bit_texts, byte_table, interleave


@given(st.integers(0, 0xFFFF), st.integers(0, 2100))
def test_address_pieces_of_a_block_wrapping_or_not(start: int, count: int) -> None:
    addresses = RegisterList(start, [0] * count).addresses  # a range, or a list when it wraps past 65535
    pieces = AddressPieces("R%d: ")
    assert pieces(addresses) == [f"R{address}: " for address in addresses]
    assert pieces(addresses) == [f"R{address}: " for address in addresses]  # from the filled table


def test_pieces_made_once_and_twice() -> None:
    words = Pieces("%d (0x%04X)\n", twice=True)
    assert words([5, 65535, 5]) == ["5 (0x0005)\n", "65535 (0xFFFF)\n", "5 (0x0005)\n"]
    assert words.cache == {5: "5 (0x0005)\n", 65535: "65535 (0xFFFF)\n"}
    assert Pieces("%s}, ")(['"40001"']) == ['"40001"}, ']


@given(st.binary(max_size=260), st.data())
def test_bit_texts_are_the_bits_least_significant_first(packed: bytes, data: st.DataObject) -> None:
    count = data.draw(st.integers(0, len(packed) * 8))
    texts = list(bit_texts(byte_table("0", "1"), packed, count))
    assert texts == [str(packed[index >> 3] >> (index & 7) & 1) for index in range(count)]


@given(st.integers(0, 0xFFFF), st.binary(max_size=260), st.data())
def test_bit_runs_are_one_text_per_bit_at_its_address(start: int, packed: bytes, data: st.DataObject) -> None:
    count = data.draw(st.integers(0, min(len(packed) * 8, 0x10000 - start)))
    runs = BitRuns("B%d=", "0;", "1;")
    expected = "".join(f"B{start + index}={packed[index >> 3] >> (index & 7) & 1};" for index in range(count))
    assert runs(start, packed, count) == expected
    assert runs(start, packed, count) == expected  # from the kept bytes


def test_interleave_takes_one_piece_per_column_in_turn() -> None:
    assert interleave((["a", "b"], iter(["1", "2"]), ["x", "y"]), 2) == "a1xb2y"
    assert interleave(([], []), 0) == ""


def test_coils_at_the_top_of_the_address_space_wrap_in_the_detail() -> None:
    from dissector.model import Frame, Kind

    frame = Frame(0, bytes.fromhex("01010203"), None, Kind.RESPONSE, 1, 1, 0, 0)
    frame.bits = BitList(65534, b"\x05", 4)
    text = detail_text(frame)
    assert "            65534: 1\n            65535: 0\n            0: 1\n            1: 0\n" in text
