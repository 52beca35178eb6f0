"""A real tessera-server for the Blender add-on's tests, started as
tests/python/conftest.py starts it: 127.0.0.1, an ephemeral port (--port 0,
read back from --port-file), a data directory under the test's temporary
root, an admin token file. `restart()` stops it and starts it again on the
same port and data (a server that goes away and comes back)."""

import os
import signal
import subprocess
import time

ADMIN_TOKEN = "admin-token-for-blender-tests"
START_SECONDS = 20
STOP_SECONDS = 20


class Server:
    def __init__(self, binary, root):
        self.binary = binary
        self.root = root
        self.data = os.path.join(root, "data")
        self.token_file = os.path.join(root, "admin.token")
        self.log_path = os.path.join(root, "server.log")
        with open(self.token_file, "w") as f:
            f.write(ADMIN_TOKEN + "\n")
        self.port = 0
        self.process = None
        self.start()

    def start(self):
        port_file = os.path.join(self.root, "port")
        if os.path.exists(port_file):
            os.unlink(port_file)
        args = [self.binary, "--data", self.data, "--port", str(self.port), "--port-file", port_file,
                "--admin-token-file", self.token_file]
        with open(self.log_path, "ab") as log:
            self.process = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=log)
        deadline = time.monotonic() + START_SECONDS
        while time.monotonic() < deadline:
            try:
                with open(port_file) as f:
                    text = f.read().strip()
                if text and int(text) > 0:
                    self.port = int(text)
                    return
            except (FileNotFoundError, ValueError):
                pass
            if self.process.poll() is not None:
                raise RuntimeError(f"tessera-server exited at start:\n{self.log()}")
            time.sleep(0.01)
        raise RuntimeError(f"tessera-server gave no port within {START_SECONDS} s:\n{self.log()}")

    def log(self):
        with open(self.log_path, errors="replace") as f:
            return f.read()

    def stop(self):
        if self.process is not None and self.process.poll() is None:
            self.process.send_signal(signal.SIGTERM)
            try:
                self.process.wait(timeout=STOP_SECONDS)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait(timeout=STOP_SECONDS)

    def restart(self):
        self.stop()
        self.start()
