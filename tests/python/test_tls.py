"""TLS (docs/PROTOCOL.md section 1): a server with a self-signed certificate
made by Debian's openssl tool, as tests/integration/certificates.h makes it."""

import pathlib
import subprocess
import tempfile

import pytest

import tessera
from conftest import ADMIN_TOKEN, Server, server_binary


@pytest.fixture(scope="module")
def tls_server():
    certificate_dir = tempfile.TemporaryDirectory(prefix="tessera-python-tls-")
    d = pathlib.Path(certificate_dir.name)
    pem, key = d / "server.pem", d / "server.key"
    subprocess.run(
        ["openssl", "req", "-x509", "-newkey", "rsa:2048", "-nodes", "-days", "1", "-subj", "/CN=127.0.0.1",
         "-addext", "subjectAltName=IP:127.0.0.1", "-keyout", str(key), "-out", str(pem)],
        check=True, capture_output=True, timeout=60)
    try:
        s = Server(server_binary(), ["--tls-cert", str(pem), "--tls-key", str(key)])
        try:
            yield s, pem
        finally:
            s.stop()
    finally:
        certificate_dir.cleanup()


def test_tls_with_the_servers_certificate_trusted(tls_server):
    server, pem = tls_server
    with tessera.Session.connect("127.0.0.1", server.port, ADMIN_TOKEN, tls_ca_file=str(pem), timeout=20) as s:
        assert s.role == "admin"
        assert s.list_documents() == []


def test_tls_refuses_a_certificate_nobody_trusts(tls_server):
    server, _ = tls_server
    with pytest.raises(tessera.Error) as refused:
        tessera.Session.connect("127.0.0.1", server.port, ADMIN_TOKEN, tls=True, timeout=20)
    assert "TLS handshake with 127.0.0.1 failed" in str(refused.value)
