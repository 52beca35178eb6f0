"""The real tessera-server for the Python package's tests.

Started as tests/integration/server_process.cc starts it: the binary named
by TESSERA_SERVER, on 127.0.0.1 with an ephemeral port (--port 0, read back
from --port-file), a fresh data directory, and an admin token written to the
file given as --admin-token-file. Every wait is bounded; the server is
stopped (SIGTERM, then SIGKILL) and its directory removed at the end.
"""

import os
import pathlib
import shutil
import signal
import subprocess
import tempfile
import time

import pytest

ADMIN_TOKEN = "admin-token-for-tests"
START_SECONDS = 20
STOP_SECONDS = 20
SAMPLES = pathlib.Path(__file__).resolve().parents[2] / "deploy" / "samples"


class Server:
    def __init__(self, binary, extra_args=()):
        self.root = tempfile.mkdtemp(prefix="tessera-python-tests-")
        data = os.path.join(self.root, "data")
        port_file = data + ".port"
        token_file = data + ".admin"
        self.log_path = data + ".log"
        with open(token_file, "w") as f:
            f.write(ADMIN_TOKEN + "\n")
        args = [binary, "--data", data, "--port", "0", "--port-file", port_file,
                "--admin-token-file", token_file, *extra_args]
        with open(self.log_path, "ab") as log:
            self.process = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=log)
        self.port = self._wait_for_port(port_file)

    def _wait_for_port(self, port_file):
        deadline = time.monotonic() + START_SECONDS
        while time.monotonic() < deadline:
            try:
                with open(port_file) as f:
                    text = f.read().strip()
                if text and int(text) > 0:
                    return int(text)
            except (FileNotFoundError, ValueError):
                pass
            if self.process.poll() is not None:
                log = self.log()
                self.stop()
                pytest.fail(f"tessera-server exited at start ({self.process.returncode}):\n{log}")
            time.sleep(0.01)
        log = self.log()
        self.stop()
        pytest.fail(f"tessera-server did not report its port within {START_SECONDS} s:\n{log}")

    def log(self):
        try:
            with open(self.log_path, errors="replace") as f:
                return f.read()
        except FileNotFoundError:
            return ""

    def stop(self):
        if self.process.poll() is None:
            self.process.send_signal(signal.SIGTERM)
            try:
                self.process.wait(timeout=STOP_SECONDS)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait(timeout=STOP_SECONDS)
        shutil.rmtree(self.root, ignore_errors=True)


def server_binary():
    binary = os.environ.get("TESSERA_SERVER")
    if not binary:
        pytest.fail("TESSERA_SERVER must name the tessera-server binary (ctest sets it)")
    return binary


@pytest.fixture(scope="session")
def server():
    s = Server(server_binary())
    try:
        yield s
    finally:
        s.stop()


@pytest.fixture
def session(server):
    import tessera

    s = tessera.Session.connect("127.0.0.1", server.port, ADMIN_TOKEN, name="pytest", timeout=20)
    try:
        yield s
    finally:
        s.close()


@pytest.fixture
def cube(session):
    """A fresh Loop document of deploy/samples/cube.obj (no tags), opened."""
    ack = session.create_document(str(SAMPLES / "cube.obj"), name="cube", max_level=4)
    session.open_document(ack.document_id)
    return ack.document_id


@pytest.fixture
def tmp_path():
    """A directory of the test's own, removed after it. pytest's own
    tmp_path keeps the last runs' directories under TMPDIR, and the suite
    must leave TMPDIR as it found it (deploy/test.sh)."""
    path = pathlib.Path(tempfile.mkdtemp(prefix="tessera-pytest-"))
    yield path
    shutil.rmtree(path, ignore_errors=True)
