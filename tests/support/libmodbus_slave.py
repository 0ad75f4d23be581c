"""A real libmodbus RTU slave (Debian's libmodbus-dev) built from a few lines of C, for tests that put vw3-decode
and the plugin against a peer no one here wrote: test_report_server_id (FC17), test_peer_mbpoll_libmodbus."""
from __future__ import annotations

import subprocess
from pathlib import Path

from lua_harness import ensure_tool, install_package

# The slave: `slave PTY` answers as slave 17 at 19200 baud from the mapping MAPPING sets up, printing libmodbus's
# version first (the test waits for it: then the slave listens); a CRC error is passed over as libmodbus does.
_SOURCE = r"""
#include <modbus.h>
#include <stdio.h>
#include <errno.h>
int main(int argc, char **argv) {
    modbus_t *ctx = modbus_new_rtu(argv[1], 19200, 'N', 8, 1);
    if (ctx == NULL || modbus_set_slave(ctx, 17) < 0 || modbus_connect(ctx) < 0) {
        fprintf(stderr, "libmodbus: %s\n", modbus_strerror(errno));
        return 1;
    }
    MAPPING
    uint8_t query[MODBUS_RTU_MAX_ADU_LENGTH];
    printf("%s\n", LIBMODBUS_VERSION_STRING);
    fflush(stdout);
    for (;;) {
        int n = modbus_receive(ctx, query);
        if (n > 0) modbus_reply(ctx, query, n, map);
        else if (n < 0 && errno != EMBBADCRC) break;
    }
    return 0;
}
"""


def build_slave(tmp_path: Path, mapping: str) -> Path:
    """The slave compiled in tmp_path, `mapping` the C that declares and fills `modbus_mapping_t *map`
    (installs libmodbus-dev where missing, as ensure_tool a tool: CI runs as root)."""
    pkg_config = ensure_tool("pkg-config", "pkg-config")
    install_package("libmodbus-dev", lambda: subprocess.run([pkg_config, "--exists", "libmodbus"]).returncode == 0,
                    "libmodbus")
    source = tmp_path / "slave.c"
    source.write_text(_SOURCE.replace("MAPPING", mapping), encoding="utf-8")
    flags = subprocess.run(["pkg-config", "--cflags", "--libs", "libmodbus"], capture_output=True, text=True,
                           check=True).stdout.split()
    binary = tmp_path / "slave"
    subprocess.run([ensure_tool("cc", "gcc"), str(source), "-o", str(binary), *flags], check=True)
    return binary
