// The page's module (crates/bumpmap-web) on a thread of its own, so the page answers clicks and
// drags while a frame is drawn or a map made. The page sends {id, op, args}; each op answers
// {id, ...} in the order asked. The file the user gave is kept here (sent once, not with each
// frame). A trap (the module aborted: out of its memory, most likely) leaves the module
// unusable: a fresh one is started, the file is forgotten, and the answer says {trapped}.

const utf8 = new TextEncoder();
const module = fetch("bumpmap_web.wasm").then((r) => r.arrayBuffer()).then((b) => WebAssembly.compile(b));
let bm = null;
let ready = start();
let file = null; // { name (UTF-8), bytes } of the user's own heights, normal map or model

async function start() {
  bm = (await WebAssembly.instantiate(await module, {})).exports;
}

// Copies `data` into the module's memory; [pointer, length] ([0, 0] for nothing).
function put(data) {
  if (!data || data.length === 0) return [0, 0];
  const ptr = bm.bm_alloc(data.length);
  if (ptr === 0) {
    throw new Error(`the page's module cannot hold ${(data.length / 2 ** 20).toFixed(0)} MiB more (it has 4 GiB at most)`);
  }
  new Uint8Array(bm.memory.buffer, ptr, data.length).set(data);
  return [ptr, data.length];
}

// The module's answer to its last call, copied out, with the frame's size where it is one.
function answer(status) {
  const bytes = new Uint8Array(bm.memory.buffer, bm.bm_answer_ptr(), bm.bm_answer_len()).slice();
  return { status, answer: bytes, width: bm.bm_answer_width(), height: bm.bm_answer_height() };
}

// Calls `fn` with the buffers `inputs` (Uint8Arrays or null) as pointer-length pairs, then
// `rest`, and gives the buffers back.
function call(fn, inputs, ...rest) {
  const held = inputs.map(put);
  try {
    return answer(bm[fn](...held.flat(), ...rest));
  } finally {
    for (const [ptr, len] of held) if (ptr) bm.bm_free(ptr, len);
  }
}

const name = () => file && file.name;
const bytes = () => file && file.bytes;

const ops = {
  // A closed set's names (0 techniques, 1 scenes, 2 presets), one a line.
  names: (set) => answer(bm.bm_names(set)),
  // The user's file, or none.
  setFile: (fileName, contents) => {
    file = fileName ? { name: utf8.encode(fileName), bytes: contents } : null;
    return { status: 0 };
  },
  // Prepares the scene `options` describe (with the file, where one was given and `withFile`).
  view: (options, withFile = true) =>
    call("bm_view", [utf8.encode(options), withFile ? name() : null, withFile ? bytes() : null]),
  // Draws the prepared scene with the light and camera turned.
  draw: (turns) => answer(bm.bm_view_draw(...turns)),
  // A file `bumpmap normalmap` writes (`which`: the library's MapFile, in its order).
  mapFile: (args, preset, which) => call("bm_map_file", [utf8.encode(args), name(), bytes(), utf8.encode(preset)], which),
  // `inspect`'s verdict on the file.
  inspect: () => call("bm_inspect", [name(), bytes()]),
  // What a trap does (as a module out of memory ends in), without one: for the tests.
  trap: () => {
    throw new WebAssembly.RuntimeError("unreachable (a test's)");
  },
};

async function handle({ id, op, args }) {
  await ready;
  try {
    const reply = ops[op](...args);
    postMessage({ id, ...reply }, reply.answer ? [reply.answer.buffer] : []);
  } catch (e) {
    if (e instanceof WebAssembly.RuntimeError) {
      file = null;
      ready = start();
      postMessage({ id, trapped: e.message });
    } else {
      postMessage({ id, error: e.message });
    }
  }
}

// One message at a time, in order: a restart after a trap finishes before the next call.
let queue = Promise.resolve();
onmessage = ({ data }) => {
  queue = queue.then(() => handle(data));
};
