#!/usr/bin/env python3
"""Runs clang-tidy over source files with a cache of clean results (used by scripts/lint.sh).

A file is checked again unless an earlier run found it clean with exactly the same input. The key
of a file is a SHA-256 over everything clang-tidy's verdict depends on:
  - the translation unit preprocessed by clang++ of clang-tidy's version with the file's own compile
    flags and comments kept (-E -C): the file and every header it includes, as that compiler sees
    them, with their NOLINT comments and line markers; a changed header changes the key of every
    file that includes it, and a removed NOLINT changes it too;
  - the file's path and its compile command from the compile database;
  - every .clang-tidy from the file's folder up to the root (the one clang-tidy uses is among them);
  - `clang-tidy --version` and the clang-tidy arguments;
  - the version of this key (KEY_VERSION).
Paths inside the checkout (--root) enter the key relative to it, in the preprocessed text too (line
markers, __FILE__), so a clone of the same commit at another path (CI's) finds the results of this one.
Only clean results are stored (an empty file named by the key): a file with any finding, or one
clang-tidy or the preprocessor failed on, has no entry and is checked on every run. A cache hit
refreshes the entry's time; entries not used for 30 days are removed.

Usage: tidy_cache.py --build DIR --logs DIR [--root DIR] [--jobs N] [--cache DIR | --no-cache] FILE...
  --build   folder with compile_commands.json
  --root    the checkout, whose path the key leaves out (default: the current folder)
  --logs    folder for one log per file clang-tidy failed on (name: path with '/' as '_', .log)
  --cache   default $KNIT_TIDY_CACHE_DIR, else ${XDG_CACHE_HOME:-~/.cache}/knit-clang-tidy
  --no-cache  check every file (also KNIT_TIDY_CACHE=OFF)
Prints one summary line: files, clean from the cache, checked. Exit status 0 unless the arguments
or the compile database are unusable; the findings are in the logs.
"""
import argparse
import concurrent.futures
import hashlib
import json
import os
import shlex
import shutil
import subprocess
import sys
import time

KEY_VERSION = b"knit-tidy-cache 2\n"
TIDY_ARGS = ["--quiet", "--warnings-as-errors=*"]
MAX_AGE_DAYS = 30


def default_cache():
    if os.environ.get("KNIT_TIDY_CACHE_DIR"):
        return os.environ["KNIT_TIDY_CACHE_DIR"]
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "knit-clang-tidy")


def tidy_version():
    return subprocess.run(["clang-tidy", "--version"], capture_output=True, check=True).stdout


def clang_for(version_text):
    """clang++ of clang-tidy's major version (its preprocessor is clang-tidy's), else clang++."""
    for word in version_text.decode(errors="replace").split():
        if word[:1].isdigit() and "." in word:
            named = "clang++-" + word.split(".")[0]
            if shutil.which(named):
                return named
            break
    return "clang++"


def load_database(build):
    path = os.path.join(build, "compile_commands.json")
    with open(path, encoding="utf-8") as f:
        entries = json.load(f)
    db = {}
    for e in entries:
        args = e["arguments"] if "arguments" in e else shlex.split(e["command"])
        file = os.path.normpath(os.path.join(e["directory"], e["file"]))
        db[file] = (e["directory"], args)
    return db


def preprocess_args(clang, args):
    """The compile command turned into `clang++ ... -E -C -o -`: same flags, no object file."""
    out = [clang]
    skip = False
    for a in args[1:]:
        if skip:
            skip = False
            continue
        if a == "-o":
            skip = True
            continue
        if a == "-c" or (a.startswith("-o") and len(a) > 2):
            continue
        out.append(a)
    return out + ["-E", "-C", "-o", "-"]


def config_files(file):
    """Contents of every .clang-tidy from the file's folder up to the root, nearest first."""
    parts = []
    folder = os.path.dirname(file)
    while True:
        candidate = os.path.join(folder, ".clang-tidy")
        if os.path.isfile(candidate):
            with open(candidate, "rb") as f:
                parts.append(candidate.encode() + b"\0" + f.read())
        parent = os.path.dirname(folder)
        if parent == folder:
            return parts
        folder = parent


def relative_to(root):
    """bytes -> bytes with the checkout's path (as given and resolved) replaced by a placeholder:
    every path below it, and the path itself as a whole string; a sibling folder whose name starts
    with the root's name is left alone."""
    roots = {os.path.abspath(root).encode(), os.path.realpath(root).encode()}

    def rewrite(data):
        for r in roots:
            data = data.replace(r + b"/", b"<root>/").replace(b'"' + r + b'"', b'"<root>"')
        return b"<root>" if data in roots else data
    return rewrite


def key_of(file, entry, clang, version, rewrite):
    """The cache key of a file, or None when it cannot be preprocessed (then it is always checked)."""
    directory, args = entry
    h = hashlib.sha256()
    h.update(KEY_VERSION)
    h.update(version)
    h.update(rewrite(json.dumps([TIDY_ARGS, file, directory, args]).encode()))
    for part in config_files(file):
        h.update(b"\0config\0" + rewrite(part))
    proc = subprocess.run(preprocess_args(clang, args), cwd=directory, stdout=subprocess.PIPE,
                          stderr=subprocess.DEVNULL, check=False)
    h.update(b"\0unit\0")
    h.update(rewrite(proc.stdout))
    return h.hexdigest() if proc.returncode == 0 else None


def check(file, db, build, logs, cache, clang, version, rewrite):
    """'cached', 'clean' or 'failed' for one file."""
    entry = db.get(file)
    key = key_of(file, entry, clang, version, rewrite) if (cache and entry) else None
    stamp = os.path.join(cache, key[:2], key) if key else None
    if stamp and os.path.exists(stamp):
        os.utime(stamp)
        return "cached"
    result = subprocess.run(["clang-tidy", "-p", build] + TIDY_ARGS + [file], capture_output=True)
    if result.returncode == 0:
        if not stamp:
            return "clean, no key" if cache else "clean"
        os.makedirs(os.path.dirname(stamp), exist_ok=True)
        open(stamp, "wb").close()
        return "clean"
    rel = os.path.relpath(file)
    with open(os.path.join(logs, rel.replace("/", "_") + ".log"), "wb") as f:
        f.write(result.stdout + result.stderr)
    return "failed"


def prune(cache):
    limit = time.time() - MAX_AGE_DAYS * 86400
    for folder, _, names in os.walk(cache):
        for name in names:
            path = os.path.join(folder, name)
            try:
                if os.path.getmtime(path) < limit:
                    os.remove(path)
            except OSError:
                pass


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--build", required=True)
    p.add_argument("--logs", required=True)
    p.add_argument("--root", default=".")
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--cache", default=default_cache())
    p.add_argument("--no-cache", action="store_true")
    p.add_argument("files", nargs="+")
    a = p.parse_args()
    use_cache = not a.no_cache and os.environ.get("KNIT_TIDY_CACHE", "ON") != "OFF"
    cache = os.path.abspath(a.cache) if use_cache else None
    build = os.path.abspath(a.build)
    db = load_database(build)
    version = tidy_version()
    clang = clang_for(version)
    files = [os.path.abspath(f) for f in a.files]
    rewrite = relative_to(a.root)
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as pool:
        verdicts = list(pool.map(lambda f: check(f, db, build, a.logs, cache, clang, version, rewrite), files))
    if cache:
        prune(cache)
    cached = verdicts.count("cached")
    where = f"cache {cache}" if cache else "no cache"
    print(f"  clang-tidy: {len(files)} files: {cached} clean in the cache, {len(files) - cached} checked ({where})")
    unkeyed = verdicts.count("clean, no key")
    if unkeyed:
        print(f"  clang-tidy: warning: {unkeyed} clean files could not be preprocessed for their cache key; "
              "they are checked on every run")
    return 0


if __name__ == "__main__":
    sys.exit(main())
