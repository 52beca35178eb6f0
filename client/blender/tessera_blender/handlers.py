"""What runs without a button: the poll timer and Blender's undo.

- `tick()` runs every POLL_SECONDS (bpy.app.timers): it reads the
  session's messages and rewrites the objects of documents that changed
  (others' edits), reconnects after a lost connection, and, when an
  operator has finished since the last tick (a new entry in
  window_manager.operators: a move is registered when the user releases
  it, not while dragging), diffs the cage and the limit object against
  the server's last state and sends what changed as one edit batch, and
  sends the cage's selection as presence.
- Blender's own undo and redo (undo_post, redo_post) never send edits:
  they restore the cage to the last state known to be the server's, so
  Blender's undo of a move that was already sent leaves the document as
  it is; Tessera's undo is the panel's (Ctrl+Alt+Z).
"""

import bpy
from bpy.app.handlers import persistent

from .connection import CONNECTION

POLL_SECONDS = 0.1
last_operator = [0]


def last_operator_pointer():
    wm = bpy.context.window_manager
    if wm is None or len(wm.operators) == 0:
        return 0
    return wm.operators[-1].as_pointer()


def send_all_changes():
    """Sends each open document's changes; a refusal or a bad edit is put
    on the panel's message line (the cage is reset to the server's)."""
    for doc in list(CONNECTION.documents.values()):
        if not CONNECTION.connected:
            return
        try:
            ack = CONNECTION.run(lambda session: doc.send_changes(session, CONNECTION.tessera))
            CONNECTION.run(lambda session: doc.send_selection(session))
            if ack is not None:
                CONNECTION.set_ok(f"'{doc.name}': edits sent as version {ack.version}")
        except Exception as e:
            CONNECTION.set_error(f"'{doc.name}': {e}")


def tick():
    """One poll; the timer's function (returns the delay to the next). An
    exception would unregister the timer, so any failure (a document's
    object deleted by the user, say) goes to the panel's message line."""
    try:
        pointer = last_operator_pointer()
        if pointer != last_operator[0]:
            last_operator[0] = pointer
            send_all_changes()
        if CONNECTION.poll():
            redraw()
    except Exception as e:
        CONNECTION.set_error(f"Tessera: {e}")
    return POLL_SECONDS


def redraw():
    wm = bpy.context.window_manager
    for window in (wm.windows if wm else []):
        for area in window.screen.areas:
            if area.type == "VIEW_3D":
                area.tag_redraw()


@persistent
def after_blender_undo(*_args):
    """Blender's undo reloads its data, the two objects included: the cage
    gets the server's state back, and the limit surface is rewritten from
    the session's view at the next poll."""
    for doc in CONNECTION.documents.values():
        doc.limit_version = 0
        doc.reset_cage()


def register():
    last_operator[0] = last_operator_pointer()
    bpy.app.timers.register(tick, first_interval=POLL_SECONDS, persistent=True)
    bpy.app.handlers.undo_post.append(after_blender_undo)
    bpy.app.handlers.redo_post.append(after_blender_undo)


def unregister():
    if bpy.app.timers.is_registered(tick):
        bpy.app.timers.unregister(tick)
    for handlers in (bpy.app.handlers.undo_post, bpy.app.handlers.redo_post):
        if after_blender_undo in handlers:
            handlers.remove(after_blender_undo)
