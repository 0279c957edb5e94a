// three_load.mjs — loads glTF/GLB files with three.js's GLTFLoader under node (Draco through
// DRACOLoader with the decoder shipped in three's examples/jsm/libs/draco, meshopt through
// MeshoptDecoder) and prints, per file, what three.js sees as one line "KNIT <json>":
//   {"file", "meshes", "triangles", "lines", "vertices", "lineVertices", "min": [x,y,z], "max": [x,y,z],
//    "textures": [{"slot", "width", "height", "wrapS", "wrapT"}], "alphaTest", "transparent"}
// (bounds in world space, after node transforms and dequantization; textures: every texture
// slot of the meshes' materials, alphaTest / transparent of the first textured material).
//
// Usage: node three_load.mjs <node_modules dir holding three> <file.glb|file.gltf> ...
// Exit status: 0 = every file loaded, 1 = a file failed to load, 2 = usage / three.js missing.
//
// The minimal environment node lacks for DRACOLoader: fetch() of local files (the decoder's
// .js/.wasm), ProgressEvent, and a Worker that runs the decoder's worker script in this thread (a vm context).
// For embedded textures (GLTFLoader's ImageBitmapLoader): fetch() of blob: URLs and a
// createImageBitmap() that reads a PNG's size from its header (no pixels: nothing is drawn).
import fs from 'node:fs';
import path from 'node:path';
import vm from 'node:vm';
import { pathToFileURL } from 'node:url';

const [modules, ...files] = process.argv.slice(2);
if (!modules || files.length === 0) {
    console.error('usage: node three_load.mjs <node_modules dir> <file.glb|file.gltf> ...');
    process.exit(2);
}
const threeDir = path.join(path.resolve(modules), 'three');
if (!fs.existsSync(path.join(threeDir, 'package.json'))) {
    console.error(`three.js not found in ${threeDir}`);
    process.exit(2);
}
const jsm = (p) => pathToFileURL(path.join(threeDir, 'examples', 'jsm', p)).href;
const THREE = await import(pathToFileURL(path.join(threeDir, 'build', 'three.module.js')).href);
const { GLTFLoader } = await import(jsm('loaders/GLTFLoader.js'));
const { DRACOLoader } = await import(jsm('loaders/DRACOLoader.js'));
const { MeshoptDecoder } = await import(jsm('libs/meshopt_decoder.module.js'));

// Step 1: the environment. fetch() of a local path reads the file.
const nodeFetch = globalThis.fetch;
globalThis.fetch = async (input, init) => {
    const url = typeof input === 'string' ? input : input.url;
    if (url.startsWith('blob:')) return new Response(blobSources.get(url));
    if (/^[a-z]+:\/\//i.test(url) && !url.startsWith('file://')) return nodeFetch(input, init);
    const file = url.startsWith('file://') ? new URL(url) : url;
    return new Response(fs.readFileSync(file));
};
// FileLoader reports progress with ProgressEvent (a browser class).
globalThis.ProgressEvent ??= class extends Event {
    constructor(type, init = {}) {
        super(type);
        Object.assign(this, init);
    }
};
// Blob URLs hold the worker source or an embedded image; Worker runs the source in a vm context
// sharing WebAssembly.
const blobSources = new Map();
// GLTFLoader reads URL.createObjectURL through the browser's `self`.
globalThis.self ??= globalThis;
// An ImageBitmap stand-in with the PNG's width and height (IHDR: bytes 16..23, big-endian).
globalThis.createImageBitmap = async (blob) => {
    const head = new DataView(await blob.slice(0, 24).arrayBuffer());
    if (head.byteLength < 24 || head.getUint32(0) !== 0x89504e47) throw new Error('embedded image is not a PNG');
    return { width: head.getUint32(16), height: head.getUint32(20), close() {} };
};
const createObjectURL = URL.createObjectURL;
URL.createObjectURL = (blob) => {
    const url = createObjectURL(blob);
    blobSources.set(url, blob);
    return url;
};
globalThis.Worker = class {
    constructor(url) {
        this.onmessage = null;
        this.ready = blobSources.get(url).text().then((source) => {
            const context = { console, WebAssembly, setTimeout, clearTimeout, Promise, Uint8Array, Int8Array,
                              Uint16Array, Int16Array, Uint32Array, Int32Array, Float32Array, ArrayBuffer };
            context.self = context;
            context.postMessage = (data) => setImmediate(() => this.onmessage && this.onmessage({ data }));
            vm.createContext(context);
            vm.runInContext(source, context);
            this.context = context;
        });
    }
    postMessage(data) {
        this.ready.then(() => this.context.onmessage({ data }));
    }
    terminate() {}
};

// Step 2: the loaders.
const draco = new DRACOLoader();
draco.setDecoderPath(pathToFileURL(path.join(threeDir, 'examples', 'jsm', 'libs', 'draco')).href + '/');
const loader = new GLTFLoader();
loader.setDRACOLoader(draco);
loader.setMeshoptDecoder(MeshoptDecoder);

// Step 3: load each file and summarize what three.js built.
function describeTextures(s, material) {
    for (const slot of ['map', 'normalMap', 'aoMap', 'roughnessMap', 'metalnessMap', 'emissiveMap']) {
        const t = material[slot];
        if (!t) continue;
        s.textures ??= [];
        s.textures.push({ slot, width: t.image.width, height: t.image.height, wrapS: t.wrapS, wrapT: t.wrapT });
        s.alphaTest ??= material.alphaTest;
        s.transparent ??= material.transparent;
    }
}

function summarize(file, gltf) {
    const s = { file, meshes: 0, triangles: 0, lines: 0, vertices: 0, lineVertices: 0 };
    const box = new THREE.Box3();
    gltf.scene.updateMatrixWorld(true);
    gltf.scene.traverse((o) => {
        if (!o.geometry) return;
        const g = o.geometry;
        const n = g.attributes.position.count;
        if (o.isMesh) {
            describeTextures(s, o.material);
            s.meshes += 1;
            s.vertices += n;
            s.triangles += (g.index ? g.index.count : n) / 3;
        } else if (o.isLine) {
            s.lines += 1;
            s.lineVertices += n;
        }
        box.expandByObject(o, true);
    });
    s.min = box.min.toArray();
    s.max = box.max.toArray();
    return s;
}

let failed = false;
for (const file of files) {
    try {
        const data = fs.readFileSync(file);
        const buffer = data.buffer.slice(data.byteOffset, data.byteOffset + data.byteLength);
        const gltf = await loader.parseAsync(buffer, pathToFileURL(path.dirname(path.resolve(file))).href + '/');
        console.log('KNIT ' + JSON.stringify(summarize(file, gltf)));
    } catch (e) {
        console.log('KNIT ' + JSON.stringify({ file, error: String(e && e.stack ? e.stack : e) }));
        failed = true;
    }
}
draco.dispose();
process.exit(failed ? 1 : 0);
