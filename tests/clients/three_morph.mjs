// three_morph.mjs — plays `knit animate -o out.glb` in three.js under node: the GLTFLoader's
// animation clip must have one key per frame, and at the time of key k the AnimationMixer's
// morph weights applied to the geometry (base + sum of influence x relative morph target, in
// world space) must give frame k's points of the matching PC2 point cache.
//
// Usage: node three_morph.mjs <node_modules dir holding three> <anim.glb> <cache.pc2>
// Prints "KNIT_MORPH <json>" {"frames", "points", "maxError"}; exit 0 = match, 1 = mismatch or
// load failure, 2 = usage / three.js missing.
import fs from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const [modules, glbFile, pc2File] = process.argv.slice(2);
if (!modules || !glbFile || !pc2File) {
    console.error('usage: node three_morph.mjs <node_modules dir> <anim.glb> <cache.pc2>');
    process.exit(2);
}
const threeDir = path.join(path.resolve(modules), 'three');
if (!fs.existsSync(path.join(threeDir, 'package.json'))) {
    console.error(`three.js not found in ${threeDir}`);
    process.exit(2);
}
const THREE = await import(pathToFileURL(path.join(threeDir, 'build', 'three.module.js')).href);
const { GLTFLoader } = await import(pathToFileURL(path.join(threeDir, 'examples', 'jsm', 'loaders', 'GLTFLoader.js')).href);
globalThis.ProgressEvent ??= class extends Event {};

// Step 1: the PC2 cache, read by its specification (little-endian header, then float32 xyz).
function readPc2(file) {
    const b = fs.readFileSync(file);
    const points = b.readInt32LE(16), samples = b.readInt32LE(28);
    return { points, samples, frame: (k, i) => [0, 1, 2].map((c) => b.readFloatLE(32 + ((k * points + i) * 3 + c) * 4)) };
}

// Step 2: the animated object and its clip.
const data = fs.readFileSync(glbFile);
const gltf = await new GLTFLoader().parseAsync(data.buffer.slice(data.byteOffset, data.byteOffset + data.byteLength), '');
let object = null;
gltf.scene.traverse((o) => {
    if (o.geometry && o.geometry.morphAttributes.position) object = o;
});
const clip = gltf.animations[0];
const cache = readPc2(pc2File);
const fail = (why) => {
    console.log('KNIT_MORPH ' + JSON.stringify({ error: why }));
    process.exit(1);
};
if (!object) fail('no object with morph targets');
if (!clip || clip.tracks.length !== 1) fail('no animation clip with one track');
const times = clip.tracks[0].times;
if (times.length !== cache.samples) fail(`clip has ${times.length} keys, the cache ${cache.samples} frames`);

// Step 3: each key's pose through the mixer, compared with the cache.
const mixer = new THREE.AnimationMixer(gltf.scene);
// LoopOnce + clamp: a looping action wraps the last key's time (= the clip's duration) to 0.
const action = mixer.clipAction(clip);
action.setLoop(THREE.LoopOnce, 1);
action.clampWhenFinished = true;
action.play();
const g = object.geometry, base = g.attributes.position, targets = g.morphAttributes.position;
if (base.count !== cache.points) fail(`${base.count} vertices, the cache ${cache.points} points`);
let maxError = 0;
for (let k = 0; k < times.length; ++k) {
    mixer.setTime(times[k]);
    gltf.scene.updateMatrixWorld(true);
    const w = object.morphTargetInfluences;
    const v = new THREE.Vector3();
    for (let i = 0; i < base.count; ++i) {
        v.fromBufferAttribute(base, i);
        for (let t = 0; t < targets.length; ++t) {
            if (w[t] === 0) continue;
            v.x += w[t] * targets[t].getX(i);
            v.y += w[t] * targets[t].getY(i);
            v.z += w[t] * targets[t].getZ(i);
        }
        v.applyMatrix4(object.matrixWorld);
        const c = cache.frame(k, i);
        maxError = Math.max(maxError, Math.hypot(v.x - c[0], v.y - c[1], v.z - c[2]));
    }
}
console.log('KNIT_MORPH ' + JSON.stringify({ frames: times.length, points: base.count, maxError }));
process.exit(maxError <= 1e-5 ? 0 : 1);
