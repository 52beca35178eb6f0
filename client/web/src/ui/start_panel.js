// The panel in the middle of the page before a document is shown: a token
// field when the address has no #token=, the list of documents the token
// may open when it has no ?doc=, and a refusal (an unknown token) with the
// field again. Hidden once a document is chosen.
export class StartPanel {
  constructor(root) {
    this.root = root;
    root.classList.add('start');
    root.hidden = true;
  }

  hide() {
    this.root.hidden = true;
  }

  show(...children) {
    this.root.replaceChildren(...children);
    this.root.hidden = false;
  }

  // Calls onToken(token) with what the user typed; `problem` says why it is
  // asked again.
  askToken(onToken, problem = '') {
    const form = document.createElement('form');
    form.innerHTML = `<h1>Tessera</h1>
      <p>An access token is needed to open documents.</p>
      <p class="start-problem"></p>
      <input type="password" name="token" autocomplete="off" placeholder="access token" aria-label="access token" required>
      <button type="submit">Connect</button>`;
    form.querySelector('.start-problem').textContent = problem;
    form.addEventListener('submit', (event) => {
      event.preventDefault();
      const token = form.elements.token.value.trim();
      if (token) onToken(token);
    });
    this.show(form);
    form.elements.token.focus();
  }

  // documents: [{id: BigInt, name, version: BigInt}]; calls onChoose(id).
  listDocuments(documents, onChoose) {
    const box = document.createElement('div');
    box.innerHTML = '<h1>Tessera</h1><p>Choose a document</p>';
    if (documents.length === 0) {
      box.append(Object.assign(document.createElement('p'), { textContent: 'This token may open no document.' }));
    }
    const list = document.createElement('ul');
    list.className = 'start-documents';
    for (const d of documents) {
      const li = document.createElement('li');
      const button = document.createElement('button');
      button.textContent = `${d.name || 'unnamed'}`;
      const meta = document.createElement('span');
      meta.textContent = `document ${d.id} · version ${d.version}`;
      button.append(meta);
      button.addEventListener('click', () => onChoose(d.id));
      li.append(button);
      list.append(li);
    }
    box.append(list);
    this.show(box);
  }

  message(text) {
    const p = document.createElement('p');
    p.textContent = text;
    this.show(p);
  }
}
