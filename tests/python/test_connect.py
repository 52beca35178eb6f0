"""Connecting and authenticating (docs/PROTOCOL.md section 4)."""

import pytest

import tessera
from conftest import ADMIN_TOKEN


def test_the_admin_token_connects_as_admin(server):
    with tessera.Session.connect("127.0.0.1", server.port, ADMIN_TOKEN, name="alice", timeout=20) as s:
        assert s.role == "admin"
        assert s.session_id > 0
        assert s.ping() > 0


def test_an_unknown_token_raises_with_the_servers_message(server):
    with pytest.raises(tessera.AuthenticationFailed) as refused:
        tessera.Session.connect("127.0.0.1", server.port, "no-such-token", timeout=20)
    assert refused.value.code == "ERROR_CODE_AUTH_FAILED"
    # server/net/connection.cc's words, as the server sends them.
    assert "the access token is not known to this server" in str(refused.value)
    assert isinstance(refused.value, tessera.ServerError)
    assert isinstance(refused.value, tessera.Error)


def test_nothing_listening_is_an_error_not_a_hang(server):
    with pytest.raises(tessera.Error) as failed:
        tessera.Session.connect("127.0.0.1", 1, ADMIN_TOKEN, timeout=5)
    assert "cannot connect to 127.0.0.1:1" in str(failed.value)


def test_threads_take_turns_on_one_session(session, cube):
    import threading

    versions, errors = [], []

    def edit(i):
        try:
            for k in range(5):
                versions.append(session.offset_vertices(cube, f"v0:{i}", (0.0, 0.0, 0.001)).version)
                session.ping()
        except Exception as e:  # noqa: BLE001 -- reported below
            errors.append(e)

    threads = [threading.Thread(target=edit, args=(i,)) for i in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(timeout=60)
    assert not errors
    # 20 edits after the creation's version 1: each got its own version.
    assert sorted(versions) == list(range(2, 22))


def test_a_closed_session_raises(server):
    s = tessera.Session.connect("127.0.0.1", server.port, ADMIN_TOKEN, timeout=20)
    s.close()
    assert s.closed
    with pytest.raises(tessera.Error) as closed:
        s.ping()
    assert "the session is closed" in str(closed.value)
