// A stand-in for the page's decode worker (src/codec/decode_worker.js) in
// Node: the same messages (src/codec/decode_messages.js) and the same
// decodeRegion() with the same Draco module, but answered when the test
// says, in the order it says. Messages cross as a browser's would, through
// structuredClone with the transfer list, so arrays that are not
// transferable, or shared, fail here as they would there.
import { decodeRegion } from '../../src/codec/region_decoder.js';
import { packAnswers } from '../../src/codec/decode_messages.js';

export class FakeDecodeWorker {
  constructor(draco) {
    this.draco = draco;
    this.requests = []; // {id, bytes} not answered yet, oldest first
    this.messages = 0; // messages of requests received
    this.onmessage = null;
    this.onerror = null;
    this.sentRegions = []; // the worker-side regions posted, to see them detached
  }

  // One message of requests (sent once the page's task ends); each is
  // kept to be answered on its own.
  postMessage(data, transfer = []) {
    ++this.messages;
    this.requests.push(...structuredClone(data, { transfer }).requests);
  }

  // Says it has its Draco module, as the worker does once loaded.
  start() {
    this.deliver({ ready: true, dracoLoaded: true });
  }

  // Answers the request at `index` of those waiting (0: the oldest).
  answer(index = 0) {
    const [{ id, bytes }] = this.requests.splice(index, 1);
    let region;
    try {
      region = decodeRegion(this.draco, bytes);
    } catch (error) {
      this.deliver({ answers: [{ id, error: error.message, ms: 0.5 }] });
      return;
    }
    this.sentRegions.push(region);
    const answers = [{ id, region, ms: 1 }];
    this.deliver({ answers }, packAnswers(answers));
  }

  // Answers everything waiting, newest first.
  answerAllBackwards() {
    while (this.requests.length > 0) this.answer(this.requests.length - 1);
  }

  // The worker stops, as when its script is not served.
  crash(message) {
    this.onerror?.({ message, preventDefault() {} });
  }

  deliver(data, transfer = []) {
    this.onmessage?.({ data: structuredClone(data, { transfer }) });
  }
}
