"""vw3-extcap's side of Wireshark's extcap protocol: interfaces, options, their round trip, the launcher."""
from __future__ import annotations

import io
import os
import re
import sys

import pytest

from dissector.app import extcap
from dissector.app.extcap_install import launcher_text, package_root
from dissector.errors import UsageError

PORTS = [("/dev/ttyUSB0", "FT232R {USB}\nUART\x1b[31m"), ("COM3", "USB Serial Port (COM3)"), ("/dev/ttyS0", "")]
SENTENCE = re.compile(r"^(extcap|interface|dlt|arg|value) (\{[a-z]+=[^{}\n]*\})+$")


def sentences(text: str) -> list[dict[str, str]]:
    out = []
    for line in text.splitlines():
        assert SENTENCE.match(line), line
        out.append({"sentence": line.split(" ", 1)[0], **dict(re.findall(r"\{([a-z]+)=([^{}]*)\}", line))})
    return out


def test_one_interface_per_port_and_the_socket_one() -> None:
    out = io.StringIO()
    extcap.print_interfaces(out, PORTS)
    assert out.getvalue() == (
        f"extcap {{version={extcap.__version__}}}\n"
        "interface {value=vw3-ttyUSB0}{display=Modbus serial tap: /dev/ttyUSB0 (FT232R  USB  UART [31m)}\n"
        "interface {value=vw3-COM3}{display=Modbus serial tap: COM3 (USB Serial Port (COM3))}\n"
        "interface {value=vw3-ttyS0}{display=Modbus serial tap: /dev/ttyS0}\n"
        "interface {value=vw3-socket}{display=Modbus serial tap: RTU over TCP gateway (socket://host:port)}\n"
    )
    sentences(out.getvalue())


def test_an_interface_name_finds_its_port() -> None:
    assert extcap.find_interface("vw3-COM3", PORTS).port == "COM3"
    assert extcap.find_interface("vw3-ttyUSB0", PORTS).port == "/dev/ttyUSB0"
    assert extcap.find_interface("vw3-socket", PORTS).port == ""
    if os.name == "posix":  # a port pyserial does not list, found under /dev
        assert extcap.find_interface("vw3-null", []).port == "/dev/null"
    with pytest.raises(UsageError, match=r"^no interface 'vw3-ttyUSB9' \(see vw3-extcap --extcap-interfaces\)$"):
        extcap.find_interface("vw3-ttyUSB9", PORTS)
    # Names are safe in fifo and preference names whatever the device is called.
    assert extcap.interface_name("/dev/serial/by-id/usb-FTDI:A5{X}") == "vw3-usb-FTDI_A5_X_"


@pytest.mark.parametrize("name", ["vw3-ttyUSB0", "vw3-socket"])
def test_every_dialog_value_is_accepted_by_the_capture(name: str) -> None:
    """The dialog's arguments round-trip: each option at its default and at each offered value parses."""
    out = io.StringIO()
    extcap.print_config(out, extcap.find_interface(name, PORTS))
    parsed = sentences(out.getvalue())
    args = [entry for entry in parsed if entry["sentence"] == "arg"]
    assert [int(entry["number"]) for entry in args] == list(range(len(args)))
    assert [entry["call"] for entry in args] == ["--port", "--baud", "--parity", "--stopbits", "--bytesize",
                                                "--mode", "--detect", "--detect-seconds", "--description"]
    parser = extcap.build_parser()
    base = ["--capture", "--extcap-interface", name, "--fifo", "f"]
    for entry in args:
        values = [value["value"] for value in parsed if value["sentence"] == "value" and value["arg"] == entry["number"]]
        if entry["type"] == "selector":
            defaults = [value["value"] for value in parsed if value["sentence"] == "value"
                        and value["arg"] == entry["number"] and value.get("default") == "true"]
            assert defaults == [entry["default"]]
        for value in values or [entry.get("default", "x")]:
            if entry["type"] == "boolflag":
                parsed_args = parser.parse_args([*base, entry["call"]])
            else:
                parsed_args = parser.parse_args([*base, entry["call"], value])
            assert parsed_args.capture
    defaults = parser.parse_args(base)
    # The dialog's defaults are vw3-decode --live's.
    assert (defaults.baud, defaults.parity, defaults.stopbits, defaults.bytesize, defaults.mode) == (
        19200, "E", 1, 8, "rtu")
    port = [entry for entry in args if entry["call"] == "--port"][0]
    assert port.get("default") == ("/dev/ttyUSB0" if name == "vw3-ttyUSB0" else None)
    assert port.get("required") == ("true" if name == "vw3-socket" else None)


def test_link_type() -> None:
    out = io.StringIO()
    extcap.print_dlts(out)
    assert sentences(out.getvalue()) == [{"sentence": "dlt", "number": "147", "name": "USER0",
                                          "display": "Modbus serial bytes as heard (map USER0 to vw3)"}]


def test_launchers_name_this_python_and_this_package(monkeypatch: pytest.MonkeyPatch) -> None:
    from dissector.app import extcap_install

    root = package_root()
    assert extcap_install.installed(root) == ("site-packages" in root or "dist-packages" in root)
    monkeypatch.setattr(extcap_install, "installed", lambda root: False)  # a source checkout
    posix = launcher_text(False)
    assert posix.startswith("#!/bin/sh\n")
    assert posix.endswith(f"PYTHONPATH={package_root()}${{PYTHONPATH:+:$PYTHONPATH}} "
                          f"exec {sys.executable} -m dissector.app.extcap \"$@\"\n")
    windows = launcher_text(True)
    assert windows == (f'@echo off\r\nset "PYTHONPATH={package_root()};%PYTHONPATH%"\r\n'
                       f'"{sys.executable}" -m dissector.app.extcap %*\r\n')
    # Installed in site-packages: no PYTHONPATH, which would put site-packages before the stdlib.
    monkeypatch.setattr(extcap_install, "installed", lambda root: True)
    assert launcher_text(False).endswith(f"\nexec {sys.executable} -m dissector.app.extcap \"$@\"\n")
    assert launcher_text(True) == f'@echo off\r\n"{sys.executable}" -m dissector.app.extcap %*\r\n'


def test_pip_installs_the_console_script() -> None:
    import importlib
    import tomllib
    from pathlib import Path

    project = tomllib.loads((Path(__file__).resolve().parents[2] / "pyproject.toml").read_text())
    target = project["project"]["scripts"]["vw3-extcap"]
    module, _, function = target.partition(":")
    assert getattr(importlib.import_module(module), function) is extcap.main


def test_output_is_utf8_whatever_the_locale() -> None:
    """Wireshark reads UTF-8; a Windows pipe or an ASCII locale must not turn a name into a traceback."""
    import subprocess
    from pathlib import Path

    done = subprocess.run([sys.executable, "-m", "dissector.app.extcap", "--extcap-interface", "vw3-é", "--extcap-config"],
                          cwd=Path(__file__).resolve().parents[2], capture_output=True, timeout=60,
                          env=dict(os.environ, PYTHONIOENCODING="ascii"))
    assert (done.returncode, done.stdout) == (2, b"")
    assert done.stderr == "vw3-extcap: no interface 'vw3-é' (see vw3-extcap --extcap-interfaces)\n".encode()
