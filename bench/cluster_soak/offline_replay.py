#!/usr/bin/env python3
"""The cluster journal replayed offline, by the single-node server.

The soak's driver writes the document's journal as read from JetStream
(journal.jsonl: each entry's version, author and entry bytes, which are the
same bytes as the SQLite store's journal rows: docs/CLUSTER.md "What is
stored where"). This starts a single-node tessera-server on a fresh SQLite
store, creates the same document there (the same mesh, tags and max level,
so the same base at version 1), stops it, inserts the cluster's journal
entries as the document's journal rows, starts it again (it loads the base
and replays every entry: no cluster code on that path) and asks
tessera-replay for the version and surface hash a fresh subscriber sees,
plus the surface at version 1 before the rows go in. Writes offline.json.

    python3 offline_replay.py RUN_DIR BIN_DIR REPO
"""
import base64
import json
import os
import shutil
import signal
import sqlite3
import subprocess
import sys
import tempfile
import time


def wait_port(port_file, proc, seconds=60):
    deadline = time.time() + seconds
    while time.time() < deadline:
        if os.path.exists(port_file) and open(port_file).read().strip():
            return int(open(port_file).read().strip())
        if proc.poll() is not None:
            raise RuntimeError(f"tessera-server exited with {proc.returncode}")
        time.sleep(0.1)
    raise RuntimeError("tessera-server wrote no port")


def main():
    run_dir, bin_dir, repo = sys.argv[1:4]
    work = tempfile.mkdtemp(prefix="tessera-soak-offline-")
    token_file = os.path.join(work, "admin.token")
    with open(token_file, "w") as f:
        f.write("offline-replay-admin-token-0123456789\n")
    data = os.path.join(work, "data")
    log = open(os.path.join(work, "server.log"), "a")
    result = {"ok": False}

    def start():
        port_file = os.path.join(work, "port")
        if os.path.exists(port_file):
            os.remove(port_file)
        proc = subprocess.Popen(
            [os.path.join(bin_dir, "tessera-server"), "--data", data, "--listen", "127.0.0.1", "--port", "0",
             "--port-file", port_file, "--admin-token-file", token_file, "--snapshot-every", "1000000000"],
            stdout=log, stderr=log, start_new_session=True)
        return proc, wait_port(port_file, proc)

    def stop(proc):
        os.killpg(proc.pid, signal.SIGTERM)
        try:
            proc.wait(30)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()

    def surface(port, doc):
        r = subprocess.run([os.path.join(bin_dir, "tessera-replay"), "surface", "--port", str(port), "--token-file",
                            token_file, "--document", str(doc)], capture_output=True, text=True, timeout=600)
        out = dict(line.split(" ", 1) for line in r.stdout.strip().splitlines() if " " in line)
        if r.returncode != 0:
            raise RuntimeError(f"tessera-replay surface: {r.stdout} {r.stderr}")
        return {"version": out.get("version"), "hash": "0x" + out.get("surface_hash", "")}

    proc = None
    try:
        proc, port = start()
        r = subprocess.run([os.path.join(bin_dir, "tessera"), "remote", "create", os.path.join(repo, "tests/data/cube.obj"),
                            "--tags", os.path.join(repo, "tests/data/cube.tags"), "--max-level", "5", "--port", str(port),
                            "--token-file", token_file], capture_output=True, text=True, timeout=120)
        doc = int(r.stdout.strip())
        result["base"] = surface(port, doc)
        stop(proc)
        proc = None
        entries = []
        with open(os.path.join(run_dir, "journal.jsonl")) as f:
            for line in f:
                if line.strip():
                    m = json.loads(line)
                    if not m.get("fence") and not m.get("bad"):
                        entries.append(m)
        store = os.path.join(data, "tessera.db")
        if not os.path.exists(store):
            raise RuntimeError(f"no tessera.db in {data}: {os.listdir(data)}")
        db = sqlite3.connect(store)
        with db:
            # Versions as the single node numbers its journal rows: the
            # cluster's entry version (1, 2, ...), which the checker has
            # already checked to run without a gap or a repeat.
            db.executemany("INSERT INTO journal (document_id, version, author, entry) VALUES (?, ?, ?, ?)",
                           [(doc, int(m["version"]), m["author"], base64.b64decode(m["entry"])) for m in entries])
        db.close()
        proc, port = start()
        result["replayed"] = surface(port, doc)
        result["entries"] = len(entries)
        result["ok"] = True
        stop(proc)
        proc = None
    except Exception as e:  # reported, and the checker counts it as a finding
        result["error"] = str(e)
        result["log"] = os.path.join(work, "server.log")
    finally:
        if proc is not None:
            os.killpg(proc.pid, signal.SIGKILL)
    with open(os.path.join(run_dir, "offline.json"), "w") as f:
        json.dump(result, f, indent=2)
    print(json.dumps(result))
    if result["ok"]:
        shutil.rmtree(work, ignore_errors=True)
    else:
        print(f"offline replay failed; its files are in {work}", file=sys.stderr)
    return 0 if result["ok"] else 1


if __name__ == "__main__":
    sys.exit(main())
