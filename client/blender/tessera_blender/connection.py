"""The add-on's one connection to a tessera-server, and its documents.

Every failure becomes `message`, the line the panel shows, naming what
went wrong. When the server goes away, the session is dropped and
`poll()` tries to connect again every RECONNECT_SECONDS; once it is back,
each open document is opened and subscribed again and its cage reread.
"""

import time

from . import module_path
from .live_document import LiveDocument

RECONNECT_SECONDS = 1.0
CONNECT_TIMEOUT = 5.0
MESSAGES_PER_POLL = 200
# receive(timeout=0) returns at once without reading what has arrived, so
# the poll waits this long (seconds) for each message, at most once empty.
RECEIVE_SECONDS = 0.002


class Connection:
    def __init__(self):
        self.tessera = None
        self.session = None
        self.host = ""
        self.port = 0
        self.token = ""
        self.client_name = "blender"
        self.message = "Not connected"
        self.error = False
        self.documents = {}           # document id -> LiveDocument
        self.listed = []              # DocumentInfo of the last list
        self.next_retry = 0.0
        self.lost = False

    # --- connecting -------------------------------------------------------------

    def connect(self, host, port, token, name="blender", module_dir=""):
        """Connects; raises RuntimeError (or ImportError) with the reason,
        after setting `message` to it."""
        self.close()
        try:
            self.tessera = module_path.import_tessera(module_dir)
        except ImportError as e:
            self.set_error(str(e))
            raise
        self.host, self.port, self.token, self.client_name = host, int(port), token, name
        try:
            self.session = self.open_session()
        except self.tessera.Error as e:
            self.set_error(self.describe(e))
            raise RuntimeError(self.message) from e
        self.lost = False
        self.set_ok(f"Connected to {host}:{port} as {self.session.role} (session {self.session.session_id})")

    def open_session(self):
        return self.tessera.Session.connect(self.host, self.port, self.token, name=self.client_name,
                                            timeout=CONNECT_TIMEOUT)

    def describe(self, error):
        t = self.tessera
        where = f"{self.host}:{self.port}"
        if isinstance(error, t.AuthenticationFailed):
            return f"{where} refused the token ({error.code}): check the token"
        if isinstance(error, t.Rejected):
            return f"{where} refused the command ({error.reason}): {error.message}"
        return f"{where}: {error}"

    def set_error(self, text):
        self.message, self.error = text, True

    def set_ok(self, text):
        self.message, self.error = text, False

    def close(self):
        if self.session is not None:
            try:
                self.session.close()
            except Exception:
                pass
        self.session = None

    def disconnect(self):
        self.close()
        self.documents.clear()
        self.lost = False
        self.set_ok("Not connected")

    @property
    def connected(self):
        return self.session is not None and not self.session.closed

    def require_session(self):
        if not self.connected:
            raise RuntimeError(self.message if self.error else "not connected: connect first")
        return self.session

    # --- documents --------------------------------------------------------------

    def list_documents(self):
        self.listed = self.require_session().list_documents()
        return self.listed

    def open_document(self, document_id, name, lod, edit_level, scheme="", matrix=None):
        doc = self.documents.get(document_id)
        if doc is None:
            doc = LiveDocument(document_id, name, scheme, lod, edit_level)
            doc.attach(self.require_session(), self.tessera)
            doc.make_objects(matrix)
            self.documents[document_id] = doc
        self.poll()
        return doc

    # --- the poll (bpy.app.timers) ---------------------------------------------

    def poll(self):
        """Reads what arrived, updates every document's objects; reconnects
        when the connection was lost. Returns the documents that changed."""
        if self.tessera is None:
            return []
        if not self.connected:
            if self.lost:
                self.try_reconnect()
            return []
        changed = []
        try:
            for _ in range(MESSAGES_PER_POLL):
                if self.session.receive(timeout=RECEIVE_SECONDS) is None:
                    break
            for doc in self.documents.values():
                if doc.apply_view(self.session, self.tessera):
                    changed.append(doc)
        except self.tessera.Rejected as e:
            self.set_error(self.describe(e))
        except self.tessera.Error as e:
            self.connection_lost(e)
        return changed

    def connection_lost(self, error):
        self.close()
        self.lost = True
        self.next_retry = time.monotonic() + RECONNECT_SECONDS
        self.set_error(f"Connection to {self.host}:{self.port} lost ({error}); "
                       f"reconnecting every {RECONNECT_SECONDS:g} s")

    def try_reconnect(self):
        if time.monotonic() < self.next_retry:
            return False
        self.next_retry = time.monotonic() + RECONNECT_SECONDS
        try:
            self.session = self.open_session()
            for doc in self.documents.values():
                doc.limit_version = 0
                doc.attach(self.session, self.tessera)
        except self.tessera.Error as e:
            self.close()
            self.set_error(f"Reconnecting to {self.host}:{self.port}: {self.describe(e)}; "
                           f"trying again every {RECONNECT_SECONDS:g} s")
            return False
        self.lost = False
        self.set_ok(f"Reconnected to {self.host}:{self.port}; {len(self.documents)} document(s) reopened")
        return True

    def run(self, action):
        """Runs action(session) for an operator; a lost connection is noted
        (and retried by the poll), any failure is raised with its reason."""
        session = self.require_session()
        try:
            return action(session)
        except self.tessera.Rejected as e:
            self.set_error(self.describe(e))
            raise RuntimeError(self.message) from e
        except self.tessera.Error as e:
            self.connection_lost(e)
            raise RuntimeError(self.message) from e


CONNECTION = Connection()
