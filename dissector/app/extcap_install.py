"""`vw3-extcap --install [DIR]`: the launcher Wireshark runs from its extcap folder.

Wireshark runs every executable file of its extcap folders, with no interpreter: a launcher names
this Python and this package (so a virtual environment or a source checkout works) and hands over
its arguments. On POSIX it is a shell script that `exec`s Python, so that the SIGTERM Wireshark
sends reaches Python itself. On Windows it is a copy of pip's `vw3-extcap.exe` (which ends its
Python when Wireshark ends it), or a batch file where there is none.

Without DIR, the personal extcap folder is asked of the installed tshark (`tshark -G folders`):
"Personal Extcap path" (Wireshark 4.2 and later), or "extcap" in the personal configuration folder
(4.0), the folders its About > Folders lists. WIRESHARK_CONFIG_DIR moves the latter.
"""
from __future__ import annotations

import os
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

from dissector.errors import ExitStatus, LiveError

NAME = "vw3-extcap"
_TSHARKS = ("/Applications/Wireshark.app/Contents/MacOS/tshark", r"C:\Program Files\Wireshark\tshark.exe")


def package_root() -> str:
    """The folder holding the `dissector` package (site-packages, or a source checkout)."""
    return str(Path(__file__).resolve().parents[2])


def personal_folder() -> Path:
    tshark = shutil.which("tshark") or next((path for path in _TSHARKS if os.path.exists(path)), None)
    if tshark is None:
        raise LiveError("no tshark to ask for Wireshark's personal extcap folder: give it "
                        f"({NAME} --install DIR; Wireshark's Help > About > Folders lists it)")
    try:
        done = subprocess.run([tshark, "-G", "folders"], capture_output=True, text=True, timeout=60)
    except (OSError, subprocess.TimeoutExpired) as error:
        raise LiveError(f"cannot run {tshark} -G folders: {error}", ExitStatus.ERROR) from None
    folders = {}
    for line in done.stdout.splitlines():
        key, _, value = line.partition(":")
        folders[key.strip()] = value.strip()
    if folders.get("Personal Extcap path"):
        return Path(folders["Personal Extcap path"])
    if folders.get("Personal configuration"):
        return Path(folders["Personal configuration"]) / "extcap"
    raise LiveError(f"{tshark} -G folders names no personal folder: give one ({NAME} --install DIR)")


def installed(root: str) -> bool:
    """Whether `root` is one of this Python's own site-packages (it then finds the package itself)."""
    import site
    import sysconfig

    own = {sysconfig.get_paths()[key] for key in ("purelib", "platlib")}
    own |= set(site.getsitepackages()) | {site.getusersitepackages()}
    return any(os.path.exists(path) and os.path.samefile(root, path) for path in own)


def launcher_text(windows: bool) -> str:
    """The launcher: this Python, with the package's folder on PYTHONPATH when it is not installed
    (a source checkout): never a site-packages folder, which would come before the standard library."""
    python, root = sys.executable, package_root()
    path = not installed(root)
    if windows:
        setting = f'set "PYTHONPATH={root};%PYTHONPATH%"\r\n' if path else ""
        return f'@echo off\r\n{setting}"{python}" -m dissector.app.extcap %*\r\n'
    setting = f"PYTHONPATH={shlex.quote(root)}${{PYTHONPATH:+:$PYTHONPATH}} " if path else ""
    return (
        "#!/bin/sh\n"
        f"# Wireshark's launcher for the vw3-dissector serial tap (written by {NAME} --install).\n"
        f"{setting}exec {shlex.quote(python)} -m dissector.app.extcap \"$@\"\n"
    )


def install(directory: str | None) -> Path:
    """Write the launcher into `directory` (made if missing); its path."""
    folder = Path(directory) if directory else personal_folder()
    try:
        folder.mkdir(parents=True, exist_ok=True)
        if os.name == "nt":
            exe = shutil.which(NAME)
            if exe is not None and exe.lower().endswith(".exe"):
                return Path(shutil.copyfile(exe, folder / f"{NAME}.exe"))
            target = folder / f"{NAME}.bat"
            target.write_text(launcher_text(True), encoding="utf-8", newline="")
            return target
        target = folder / NAME
        target.write_text(launcher_text(False), encoding="utf-8")
        target.chmod(0o755)
        return target
    except OSError as error:
        raise LiveError(f"cannot write into {folder}: {error.strerror or error}", ExitStatus.ERROR) from None
