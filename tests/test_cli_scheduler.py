"""``--scheduler`` at an address that is not a Dask scheduler (issue 77, point 3): the
handshake is bounded (:data:`reports.run.cluster.HANDSHAKE_S`) and the address refused,
exit 2, naming it.  Found by these probes: at a plain HTTP server the run hung (still
running after 300 s); a peer that talks first was read as a 3 EiB frame and reported as
"out of memory"."""

from __future__ import annotations

import socket
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager

import pytest
from test_cli_hostile_inputs import TINY, _answer

from reports.run import cluster


@contextmanager
def peer(greeting: bytes | None) -> Iterator[str]:
    """A TCP listener on 127.0.0.1 that accepts and says ``greeting`` (None: nothing)."""
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen()
    held: list[socket.socket] = []

    def serve() -> None:
        while True:
            try:
                conn, _ = server.accept()
            except OSError:  # closed
                return
            held.append(conn)
            if greeting is not None:
                conn.sendall(greeting)

    threading.Thread(target=serve, daemon=True).start()
    try:
        yield f"tcp://127.0.0.1:{server.getsockname()[1]}"
    finally:
        server.close()
        for conn in held:
            conn.close()


@pytest.mark.parametrize(("greeting", "needle"), [
    (None, "sent no Dask handshake within 2 s"),
    (b"SSH-2.0-OpenSSH_9.2\r\n", "answered in another protocol"),
    (b"\xff" * 8, "answered in another protocol"),  # a 2**64 - 1 byte frame
    (b"\x10\x00\x00\x00\x00\x00\x00\x00", "sent no Dask handshake"),  # then silence
], ids=["silent", "ssh", "huge-frame", "short-frame"])
def test_a_peer_that_is_not_a_scheduler_is_refused_in_bounded_time(greeting, needle,
                                                                   monkeypatch):
    with peer(greeting) as address:
        t0 = time.perf_counter()
        with pytest.raises(cluster.UserError) as err:
            cluster.probe_scheduler(address, seconds=2.0)
        assert time.perf_counter() - t0 < 10
    assert address in str(err.value) and needle in str(err.value)


def test_run_at_a_silent_peer_exits_2_naming_it(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(cluster, "HANDSHAKE_S", 2.0)
    monkeypatch.setattr(cluster.probe_scheduler, "__defaults__", (2.0,))
    case = tmp_path / "case.toml"
    case.write_text(TINY)
    with peer(None) as address:
        t0 = time.perf_counter()
        code, err = _answer(["run", str(case), "--scheduler", address, "--no-progress",
                             "--out", str(tmp_path / "o")], capsys)
        assert time.perf_counter() - t0 < 30
    assert code == 2 and f"--scheduler {address}" in err, err
    assert not (tmp_path / "o").exists()


def test_a_dask_scheduler_passes_the_probe():
    from distributed import LocalCluster

    with LocalCluster(n_workers=0, dashboard_address=None) as local:
        cluster.probe_scheduler(local.scheduler_address, seconds=10.0)


def test_an_address_nothing_listens_at_is_refused():
    with socket.socket() as s:  # a port just freed: nothing listens there
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    with pytest.raises(cluster.UserError, match="cannot reach the Dask scheduler"):
        cluster.probe_scheduler(f"tcp://127.0.0.1:{port}", seconds=2.0)
