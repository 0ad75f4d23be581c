"""`vw3-decode FILE -w COPY` of a tap's reads writes FILE's reads (sources/trail.py: an item from inside a
timed read has its first record begin where the read begins): the fixed vectors are the 14 of 2,000
random streams of test_copy_reads.py (its seeds) whose COPY decoded otherwise, a frame or noise run from
inside a read written as a record of its own. Seed 56: the noise after an exception answer ending inside
a read, alone in a record, read back as a damaged FC12 answer of slave 79; seed 244: an intact request
from inside a read, alone in a record, made the noise after it a damaged request (and the request
'[no response]'). Each COPY is FILE's records, pcap and pcapng, engine and Python stages, read in bulk,
chunk by chunk or by the Python stages byte for byte alike."""
from __future__ import annotations

from pathlib import Path

import pytest

from helpers import pcapng_packets, run_cli, use_engine
from dissector.model import Stamp
from dissector.render.pcapngwriter import PcapngWriter
from dissector.render.pcapwriter import PcapWriter
from test_copy_bulk import WAYS, copy
from test_copy_reads import T0
from test_timed_summary import write_pcap

# Seed: "microseconds:bytes" of each read.
VECTORS = {
    56: "0:9ad77630bf01060001 25157:000398 26876:0b0183 28595:02c0f1018202c0f101 34652:8302c0f14f0c030600010002 "
        "61528:0003a5e4018b 64966:02c0f10110000100021008 91269:01 94842:100001000210 98280:080c0306000100020003 "
        "124010:a5 127583:e4",
    244: "0:018302c0f10106 24011:00010003980ba88c01 49168:0600010003980b0c0306 57898:00 58471:0100020003a5e40110 "
         "83628:000300020400 87066:0100 89112:02e26201 91104:10000100020400010002 96834:e2620c0320d000030eef "
         "122564:0110020100020400010002e2 129140:62",
    330: "0:08aaac7b7d0d241b01 4857:100001000204000100 10014:02e26201 12006:1000010002 14571:10080c "
         "17190:03060001000200 22101:03 22374:a5e401100001 28812:00020400010042 32823:e2620c "
         "54542:0306000100020003a5e401 60545:1000 62591:0100020400010002e2 70748:62010600010003980b0dedc7 "
         "77324:0110 78670:00 78943:01000210 101235:08 101808:01060001 124100:0003980b",
    410: "0:010600010003980b99011000 26876:01000204 29168:00010002e2620c 36179:03 56752:8600 58798:0100020003 "
         "64663:a5e4e6334fed",
    551: "0:0c 773:0306000100020003a5e4 6503:d0cc080183 9368:22 10841:c0f1011000010002 15425:0400010002e2 "
         "38863:6258189c9fe1 42001:01 62574:8302c0f101100001000204 71877:000100 73596:02e262011000012002 "
         "79653:0400010002e2620c03 84810:20d0 85956:00030eef011000010002 91386:1008017008",
    658: "0:0110000100021008011000 6503:01 7076:00 10649:02100801100001 17660:000204000100 "
         "21998:02e2620c03060001000200 28301:03a5e4011000010002 36458:0400010102e262",
    730: "0:f951529093 2865:011000010002100801100001 29741:000210080c0320d000030e 36044:efbf011000010002 60628:04 "
         "62101:00010002e262018302c0f1",
    789: "0:0c03 846:20d000030eef01100001 6276:00020400010002e262 31433:018302c0f1018302 36017:c0f10106 "
         "39209:00012003980b01 43220:06000100 45512:0398 46858:0b010600010003980b0c 52588:0306000100020003 "
         "56872:a5e4018302c0f101c302 65602:c0f1",
    1307: "0:bba1dae20c03 4338:20d000030eef01 8349:1000010002 31214:10080110000100020400 "
          "36944:010002e262018302c0f10c 63247:03060001000200 67458:03a5e4 69177:011000010002100802 "
          "75234:931d0106000100 79245:03980b011000 102683:03000210 105875:08c94d38 108167:3d357a0c030600010002 "
          "116897:0003b5 119516:e4",
    1358: "0:01100001000204000100 5730:02e262018302c0f178 13887:87db45bb",
    1528: "0:01100001 2292:00020400010002 6303:e262 10449:010600010003980b 18033:e453414801060001000398 "
          "24036:0b01100001000210080c03 30039:0600 31385:0100020003a5e49b011000 40688:01000204 42680:00010002e262",
    1613: "0:011000010002 3438:0400010002e2620c030600 10641:0100020003a5e401060001 16644:0003980b010600 "
          "23655:010003980b 29520:0c0320d000 32385:030eef018302c0f101 57542:06000100 60734:03980b0110 "
          "66599:200100020400010002e2 72529:62",
    1666: "0:0110 1346:000100 6065:021008 10784:0c0320d000030e 14995:ef011000010002 39006:100801060001 "
          "43344:0003980b9c 46209:0110 48255:000100020400010002 73412:62620c030600010002 "
          "78269:0003a5e4011000010002 83999:1008011000 106864:0100020400010002e266 112594:01100001000204000100 "
          "119224:02e262e5 141516:d835",
    1701: "0:0110000100020400010002 7203:e2620c 11922:0306000100 15687:020003a5e40c030600010002 42563:0007a5e4 "
          "64855:01060001 87147:0003980b01 110012:100001 111431:0002040001 114496:0002e2 "
          "116215:6201100801000210080c03 123418:06000100020003a5 128902:e4 149475:0110000100021008 "
          "153759:0c0306000100020003a5e401 163635:8102c0f1",
}
BOTH = pytest.mark.parametrize("pure", [False, True], ids=["engine", "python"])


def reads_of(seed: int) -> list[tuple[int, bytes]]:
    return [(int(micros), bytes.fromhex(data)) for micros, data in
            (read.split(":") for read in VECTORS[seed].split())]


def capture(path: Path, seed: int) -> Path:
    with path.open("wb") as stream:
        writer = PcapngWriter(stream, flush=False) if path.suffix == ".pcapng" else PcapWriter(stream, flush=False)
        for micros, data in reads_of(seed):
            writer.write(data, Stamp((T0 + micros) * 1000))
    return path


def pcapng_records(path: Path) -> list[tuple[int, bytes, list[str]]]:
    """(microseconds from T0, bytes, comments) of each packet block of the copy (little-endian, in us)."""
    return pcapng_packets(path, T0)


def written(path: Path) -> list[tuple[int, bytes]]:
    """(microseconds from T0, bytes) of each record of a pcapng, the copy's closing record of no byte left out."""
    found = [(micros, data) for micros, data, _comments in pcapng_records(path)]
    return found[:-1] if found and found[-1][1] == b"" else found


def lines(*arguments: object) -> list[str]:
    status, out, err = run_cli([str(argument) for argument in arguments])
    assert (status, err) == (0, "")
    return out.splitlines()


@BOTH
@pytest.mark.parametrize("seed", list(VECTORS))
def test_a_copy_of_reads_is_its_reads(tmp_path: Path, monkeypatch: pytest.MonkeyPatch, pure: bool,
                                      seed: int) -> None:
    use_engine(monkeypatch, pure)
    original = capture(tmp_path / "reads.pcapng", seed)
    for copy_ in (tmp_path / "copy.pcap", tmp_path / "copy.pcapng"):
        assert lines(original, "-w", copy_) == []
        assert lines(copy_) == lines(original), copy_.suffix
    assert written(tmp_path / "copy.pcapng") == reads_of(seed)


@BOTH
def test_noise_after_a_frame_inside_a_read_stays_noise(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                       pure: bool) -> None:
    """Seed 56: the read 83 02 c0 f1 4f 0c 03 06 00 01 00 02 ends an exception answer, then noise. Before,
    the copy wrote the noise as a record of its own, read back as '79 response  Get Comm Event Log
    (malformed)'. The record says what it holds (pcapng comment)."""
    use_engine(monkeypatch, pure)
    original, copy_ = capture(tmp_path / "reads.pcap", 56), tmp_path / "copy.pcapng"
    lines(original, "-w", copy_)
    assert lines(copy_)[5] == "     6     0.034652   - noise     8 bytes of noise at offset 28: 4f 0c 03 06 00 01 00 02"
    assert pcapng_records(copy_)[4] == (34_652, bytes.fromhex("8302c0f14f0c030600010002"),
                                        ["then noise: 8 bytes, no valid frame"])


@BOTH
def test_a_frame_inside_a_read_leaves_the_noise_after_it_noise(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                               pure: bool) -> None:
    """Seed 244: the read e2 62 0c 03 20 d0 00 03 0e ef ends a damaged request, then an intact one. Before,
    the copy wrote the intact request as a record of its own: the 13 bytes of noise after it read back as a
    damaged FC16 request, which left the request '[no response]'."""
    use_engine(monkeypatch, pure)
    original, copy_ = capture(tmp_path / "reads.pcap", 244), tmp_path / "copy.pcap"
    lines(original, "-w", copy_)
    assert lines(copy_)[-2:] == [
        "     8     0.096834  12 request   Read Holding Registers 8400..8402 (3) [the capture ends 32.3 ms after the "
        "request, within the 1000 ms timeout: not known whether it was answered]  CRC ok",
        "     9     0.122564   - noise     13 bytes of noise at offset 68: 01 10 02 01 00 02 04 00 01 00 02 e2 62"]


@pytest.mark.parametrize("suffix", [".pcap", ".pcapng"])
def test_the_bulk_copy_is_the_copy_read_one_by_one(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                   suffix: str) -> None:
    """All the vectors one after the other (a second apart): read in bulk (the engine telling the trail of
    each block's reads), chunk by chunk and by the Python stages, the same copy byte for byte."""
    taps = [(data, (T0 + micros + index * 1_000_000) * 1000)
            for index, seed in enumerate(VECTORS) for micros, data in reads_of(seed)]
    path = tmp_path / "taps.pcap"
    write_pcap(path, taps)
    copies = {way: copy([path], tmp_path / f"{way}{suffix}", way, monkeypatch) for way in WAYS}
    assert copies["bulk"][2] > 0  # (read in bulk)
    for way in WAYS[1:]:
        assert copies["bulk"][:2] == copies[way][:2], way
