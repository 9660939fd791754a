#!/usr/bin/env python3
"""Feeds glint malformed inputs as a hostile or careless user would, and tallies the outcomes.

Usage: python3 scripts/hostile_sweep.py [--glint build/glint] [--work DIR] [--json FILE]

Surfaces: captures (COLMAP text model, capture.json), predicted priors, NeRF-synthetic
transforms, PLY import, export targets, run folders, and flag values. Every case runs one
glint command under a time limit and is judged:

  refused   non-zero exit, one clear error that names the file or flag
  accepted  exit 0 where the input is valid or meant to be taken (an RGBA prior, say)
  BAD       a crash (signal, internal check), a hang, a raw library message, an error that
            names nothing, an overlong message, an accepted input that should be refused,
            or a file outside the work folder that changed

The script makes its inputs from glint's own outputs (`glint synth`, a short `glint train`)
in a scratch folder it removes afterwards. It prints a table of totals by surface and every
BAD case, and exits 1 if there is any.
"""
import argparse
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

TIMEOUT = 60
MAX_MESSAGE = 600  # characters of output for one refusal; more is an echo of the input


def png_bytes(width, height, channels, value=128, bits=8):
    """A PNG of a constant value: grey, grey+alpha, RGB or RGBA (colour types 0, 4, 2, 6)."""
    colour_type = {1: 0, 2: 4, 3: 2, 4: 6}[channels]
    sample = bytes([value]) if bits == 8 else struct.pack(">H", value * 257)
    row = b"\x00" + sample * channels * width
    raw = row * height

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", width, height, bits, colour_type, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b"")


class Sweep:
    def __init__(self, glint, work):
        self.glint = os.path.abspath(glint)
        self.work = work
        self.results = []  # (surface, name, verdict, detail)

    def run(self, args, timeout=TIMEOUT):
        try:
            p = subprocess.run([self.glint] + args, capture_output=True, text=True, errors="replace",
                               timeout=timeout, cwd=self.work)
            return p.returncode, p.stdout + p.stderr
        except subprocess.TimeoutExpired:
            return None, ""

    def judge(self, surface, name, args, expect="refused", names=None):
        """Runs glint and records the verdict. `names`: a word the error must contain."""
        code, out = self.run(args)
        lines = [l for l in out.splitlines() if "error" in l.lower() or "problems:" in l or l.startswith("  ")]
        bad = None
        if code is None:
            bad = "hang"
        elif code < 0 or code >= 128:
            bad = "crash (exit %d)" % code
        elif "internal check" in out:
            bad = "internal check"
        elif "filesystem error" in out or "basic_string" in out or "std::" in out:
            bad = "raw library message"
        elif expect == "refused":
            if code == 0:
                bad = "accepted"
            elif names and names not in out:
                bad = "message does not name %s" % names
            elif len("\n".join(lines)) > MAX_MESSAGE:
                bad = "message of %d characters" % len("\n".join(lines))
        elif expect == "accepted" and code != 0:
            bad = "refused: " + (lines[-1][:200] if lines else out[-200:])
        verdict = "BAD" if bad else ("accepted" if code == 0 else "refused")
        detail = bad or (lines[-1][:160] if lines else "")
        self.results.append((surface, name, verdict, detail))

    # -- fixtures ------------------------------------------------------------------------

    def fresh(self, source, name):
        path = os.path.join(self.work, name)
        shutil.rmtree(path, ignore_errors=True)
        shutil.copytree(source, path, symlinks=True)
        return path

    def replace(self, path, how, payload=None):
        """Puts something else at path: a FIFO, a link to a device, a folder, bytes."""
        if os.path.lexists(path):
            if os.path.isdir(path) and not os.path.islink(path):
                shutil.rmtree(path)
            else:
                os.remove(path)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        if how == "fifo":
            os.mkfifo(path)
        elif how == "zero":
            os.symlink("/dev/zero", path)
        elif how == "folder":
            os.mkdir(path)
        elif how == "dangling":
            os.symlink(os.path.join(self.work, "nothing-here"), path)
        else:
            with open(path, "wb") as f:
                f.write(payload)

    # -- surfaces ------------------------------------------------------------------------

    def captures(self, cap):
        files = ["capture.json", "sparse/0/cameras.txt", "sparse/0/images.txt", "sparse/0/points3D.txt"]
        for rel in files:
            original = open(os.path.join(cap, rel), "rb").read()
            kinds = [("fifo", None), ("zero", None), ("folder", None), ("dangling", None), ("empty", b""),
                     ("garbage", bytes(range(256)) * 4), ("half", original[: len(original) // 2]),
                     ("nul", b"\0" * 4096), ("long line", b"1 " + b"9" * 300000 + b"\n")]
            for how, payload in kinds:
                c = self.fresh(cap, "C")
                self.replace(os.path.join(c, rel), how if payload is None else "bytes", payload)
                # No sparse points: every relative depth is dropped with a warning, and the capture trains.
                expect = "accepted" if (rel == "sparse/0/points3D.txt" and how == "empty") else "refused"
                self.judge("capture", "%s: %s" % (rel, how), ["info", c], expect)
        # capture.json values
        for body in ['{"depth": "%s"}' % ("x" * 50000000), '{"clamp_max": -1}', '{"clamp_max": 1e999}',
                     '{"nope": 1}', '[1, 2]', '{"normal_axes": null}', '{"depth": "z", "depth": "relative"}',
                     '{"photo_transfer": ' + "[" * 100000 + "]" * 100000 + "}"]:
            c = self.fresh(cap, "C")
            self.replace(os.path.join(c, "capture.json"), "bytes", body.encode())
            expect = "accepted" if '"depth": "z", "depth"' in body else "refused"
            self.judge("capture", "capture.json = %s" % body[:40], ["info", c], expect)
        # camera sizes and image names
        for width in ["1000000000", "-64", "9223372036854775808", "18446744073709551616", "0", "6.5", "0x40"]:
            c = self.fresh(cap, "C")
            path = os.path.join(c, "sparse/0/cameras.txt")
            text = open(path).read().replace(" PINHOLE 64 48 ", " PINHOLE %s 48 " % width, 1)
            self.replace(path, "bytes", text.encode())
            self.judge("capture", "cameras.txt width %s" % width, ["info", c], "refused", names=width)
        for name in ["a" * 256 + ".jpg", "b" * 10000000 + ".jpg", "../outside.jpg", "/etc/passwd", "sub/../../x.jpg",
                     "view_0001.jpg"]:
            c = self.fresh(cap, "C")
            path = os.path.join(c, "sparse/0/images.txt")
            text = open(path).read().replace("view_0003.jpg", name, 1)
            self.replace(path, "bytes", text.encode())
            self.judge("capture", "image name %s" % name[:20], ["info", c], "refused")
        # a symbolic link to a folder outside: followed, and said
        c = self.fresh(cap, "C")
        shutil.move(os.path.join(c, "images"), os.path.join(self.work, "images-elsewhere"))
        os.symlink(os.path.join(self.work, "images-elsewhere"), os.path.join(c, "images"))
        code, out = self.run(["info", c])
        ok = code == 0 and "symbolic links followed: 1" in out
        self.results.append(("capture", "images/ linked from outside", "accepted" if ok else "BAD",
                             "" if ok else "not listed: " + out[-200:]))
        shutil.rmtree(os.path.join(self.work, "images-elsewhere"), ignore_errors=True)

    def priors(self, cap):
        size = (64, 48)
        one = {"depth", "roughness", "metalness"}
        for buffer in ["normal", "depth", "roughness", "f0", "diffuse", "specular", "metalness"]:
            channels = 1 if buffer in one else 3
            cases = [("grey", png_bytes(*size, 1)), ("grey+alpha", png_bytes(*size, 2)), ("RGB", png_bytes(*size, 3)),
                     ("RGBA", png_bytes(*size, 4)), ("16-bit", png_bytes(*size, channels, bits=16)),
                     ("wrong size", png_bytes(20, 20, channels)), ("truncated", png_bytes(*size, channels)[:60]),
                     ("garbage", b"\x89PNG\r\n\x1a\n" + bytes(range(256)) * 8), ("fifo", None), ("zero", None),
                     ("folder", None), ("empty", b"")]
            for name, payload in cases:
                c = self.fresh(cap, "C")
                if buffer == "metalness":
                    shutil.rmtree(os.path.join(c, "priors", "f0"))
                path = os.path.join(c, "priors", buffer, "%s_view_0001.png" % buffer)
                how = {"fifo": "fifo", "zero": "zero", "folder": "folder"}.get(name, "bytes")
                self.replace(path, how, payload)
                layout_ok = (name == "RGB" and channels == 3) or (name == "grey" and channels == 1) or \
                    (name == "RGBA" and channels == 3) or (name == "grey+alpha" and channels == 1) or \
                    (name == "16-bit")
                # A constant 128 is no unit normal when it is not 3-channel-decodable; a
                # constant relative depth cannot be aligned (its view drops its depth).
                # A constant mid-grey normal map decodes to length ~0 everywhere: "no surface", a
                # mask over the whole view, which is taken; a constant relative depth cannot be
                # aligned and its view drops its depth with a warning.
                expect = "accepted" if layout_ok else "refused"
                self.judge("priors", "%s: %s" % (buffer, name), ["info", c], expect, names="view_0001")

    def nerf(self, nerf):
        base = json.load(open(os.path.join(nerf, "transforms_train.json")))
        variants = {
            "camera_angle_x -1": dict(base, camera_angle_x=-1), "camera_angle_x 0": dict(base, camera_angle_x=0),
            "camera_angle_x 4": dict(base, camera_angle_x=4), "camera_angle_x text": dict(base, camera_angle_x="abc"),
            "camera_angle_x null": dict(base, camera_angle_x=None),
            "camera_angle_x missing": {k: v for k, v in base.items() if k != "camera_angle_x"},
            "frames empty": dict(base, frames=[]), "frames object": dict(base, frames={}),
            "frames missing": {k: v for k, v in base.items() if k != "frames"},
            "file_path missing": dict(base, frames=[{"transform_matrix": base["frames"][0]["transform_matrix"]}]),
            "file_path ..": dict(base, frames=[dict(base["frames"][0], file_path="../x")]),
            "file_path absolute": dict(base, frames=[dict(base["frames"][0], file_path="/etc/passwd")]),
            "file_path 10 MB": dict(base, frames=[dict(base["frames"][0], file_path="a" * 10000000)]),
            "file_path number": dict(base, frames=[dict(base["frames"][0], file_path=7)]),
            "matrix 3x4": dict(base, frames=[dict(base["frames"][0], transform_matrix=[[1, 0, 0, 0]] * 3)]),
            "matrix text": dict(base, frames=[dict(base["frames"][0], transform_matrix="eye")]),
            "matrix singular": dict(base, frames=[dict(base["frames"][0], transform_matrix=[[0] * 4] * 4)]),
        }
        for name, body in variants.items():
            n = self.fresh(nerf, "N")
            self.replace(os.path.join(n, "transforms_train.json"), "bytes", json.dumps(body).encode())
            self.judge("nerf-synthetic", name, ["info", n], "refused")
        for how in ["fifo", "zero", "folder", "empty"]:
            n = self.fresh(nerf, "N")
            self.replace(os.path.join(n, "transforms_train.json"), how if how != "empty" else "bytes", b"")
            self.judge("nerf-synthetic", "transforms_train.json: " + how, ["info", n], "refused")
        for image in ["fifo", "zero", "folder", "truncated"]:
            n = self.fresh(nerf, "N")
            path = os.path.join(n, "train", "r_0.png")
            self.replace(path, image if image != "truncated" else "bytes", png_bytes(16, 12, 4)[:50])
            self.judge("nerf-synthetic", "image: " + image, ["info", n], "refused", names="r_0")

    def ply(self):
        header = "ply\nformat ascii 1.0\nelement vertex %s\nproperty float x\nproperty float y\nproperty float z\n" \
                 "property float f_dc_0\nproperty float f_dc_1\nproperty float f_dc_2\nproperty float opacity\n" \
                 "property float scale_0\nproperty float scale_1\nproperty float scale_2\nproperty float rot_0\n" \
                 "property float rot_1\nproperty float rot_2\nproperty float rot_3\nend_header\n"
        row = "0 0 0 0.1 0.2 0.3 1 -3 -3 -3 1 0 0 0\n"
        cases = {
            "valid": (header % 2 + row * 2, "accepted"),
            "two values more": (header % 2 + row.strip() + " 7 8\n" + row, "refused"),
            "one value fewer": (header % 2 + "0 0 0 0.1 0.2 0.3 1 -3 -3 -3 1 0 0\n" + row, "refused"),
            "count 2^62": (header % "4611686018427387904" + row, "refused"),
            "count -1": (header % "-1" + row, "refused"),
            "count text": (header % "many" + row, "refused"),
            "nan": (header % 1 + row.replace("0.1", "nan"), "refused"),
            "inf": (header % 1 + row.replace("0.1", "inf"), "refused"),
            "1e999": (header % 1 + row.replace("0.1", "1e999"), "refused"),
            "rows missing": (header % 3 + row, "refused"),
            "no end_header": ((header % 1).replace("end_header\n", "") + row, "refused"),
            "unknown type": ((header % 1).replace("property float x", "property quad x") + row, "refused"),
            "binary cut": ((header % 2).replace("ascii", "binary_little_endian") + "\0" * 10, "refused"),
            "garbage": ("\x00\x01\x02" * 100, "refused"),
            "empty": ("", "refused"),
        }
        for name, (text, expect) in cases.items():
            path = os.path.join(self.work, "in.ply")
            self.replace(path, "bytes", text.encode())
            # --input-layout: a header with only the shared properties is ambiguous by design.
            self.judge("ply import", name, ["export", path, "--input-layout", "3dgs", "--format", "3dgs", "-o",
                                            os.path.join(self.work, "out.ply"), "--force"], expect, names="in.ply")
        for how in ["fifo", "zero", "folder"]:
            path = os.path.join(self.work, "in.ply")
            self.replace(path, how)
            self.judge("ply import", how, ["export", path, "--format", "3dgs", "-o",
                                           os.path.join(self.work, "out.ply"), "--force"], "refused", names="in.ply")

    def exports(self, run):
        keep = os.path.join(self.work, "keep.txt")
        for fmt in ["3dgs", "spz", "compressed-ply"]:
            ext = {"3dgs": ".ply", "spz": ".spz", "compressed-ply": ".compressed.ply"}[fmt]
            targets = [("link to a file", "link", "refused"), ("link to /dev/null", "null", "refused"),
                       ("folder", "folder", "refused"), ("fifo", "fifo", "refused"),
                       ("missing folder", "deep", "accepted"), ("existing, no --force", "plain", "refused"),
                       ("existing, --force", "plainforce", "accepted"), ("name too long", "long", "refused")]
            for name, how, expect in targets:
                with open(keep, "w") as f:
                    f.write("kept")
                out = os.path.join(self.work, "out" + ext)
                if os.path.lexists(out):
                    shutil.rmtree(out) if os.path.isdir(out) and not os.path.islink(out) else os.remove(out)
                force = ["--force"]
                if how == "link":
                    os.symlink(keep, out)
                elif how == "null":
                    os.symlink("/dev/null", out)
                elif how == "folder":
                    os.mkdir(out)
                elif how == "fifo":
                    os.mkfifo(out)
                elif how == "deep":
                    out = os.path.join(self.work, "new", "deeper", "out" + ext)
                elif how in ("plain", "plainforce"):
                    open(out, "w").write("x")
                    force = [] if how == "plain" else force
                elif how == "long":
                    out = os.path.join(self.work, "o" * 300 + ext)
                self.judge("export", "%s: %s" % (fmt, name), ["export", run, "--format", fmt, "-o", out] + force,
                           expect)
                if open(keep).read() != "kept" or not os.path.exists("/dev/null") or \
                        not os.path.isfile(keep):
                    self.results.append(("export", "%s: %s changed a file it must not" % (fmt, name), "BAD", ""))

    def runs(self, run, cap):
        def fresh_run():
            return self.fresh(run, "R")
        cases = [("config.json", b"{", "refused"), ("config.json", b"[]", "refused"),
                 ("config.json", b'{"iters": -5}', "refused"), ("config.json", b'{"iters": 1e999}', "refused"),
                 ("config.json", None, "fifo"), ("checkpoint/state.bin", b"GLINTCKP", "refused"),
                 ("checkpoint/state.bin", b"", "refused"), ("checkpoint/state.bin", None, "fifo"),
                 ("checkpoint/state.bin", None, "zero"), ("log.csv", b"step,loss\n1,", "refused"),
                 ("log.csv", None, "fifo"), ("scene.ply", b"ply\n", "refused"), ("scene.ply", None, "zero")]
        for rel, payload, expect in cases:
            r = fresh_run()
            how = expect if payload is None else "bytes"
            self.replace(os.path.join(r, rel), how, payload)
            verdict = "refused" if payload is None else expect
            command = ["train", "-o", r, "--resume", "--iters", "32", "--threads", "1"] if rel != "scene.ply" else \
                ["render", r, "-o", os.path.join(self.work, "render-out"), "--spp", "1"]
            self.judge("run folder", "%s: %s" % (rel, how if payload is None else payload[:16]), command, verdict)
        # a second writer while the first trains
        r = fresh_run()
        first = subprocess.Popen([self.glint, "train", "-o", r, "--resume", "--iters", "3000", "--threads", "1"],
                                 stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, cwd=self.work)
        import time
        for _ in range(200):
            time.sleep(0.05)
            try:
                if "pid %d" % first.pid in open(os.path.join(r, ".glint-lock")).read():
                    break
            except OSError:
                pass
        self.judge("run folder", "second train --resume while one trains",
                   ["train", "-o", r, "--resume", "--iters", "3000"], "refused", names="is in use by pid")
        first.terminate()
        first.wait()

    def flags(self, cap, run):
        out = os.path.join(self.work, "flag-out.ply")
        for value in ["-1", "0", "nan", "inf", "1e999", "abc", "", "1e-400"]:
            self.judge("flags", "--exposure %r" % value,
                       ["export", run, "--format", "3dgs", "-o", out, "--force", "--exposure", value], "refused",
                       names="--exposure")
        for value in ["0", "-1", "9223372036854775808", "x"]:
            self.judge("flags", "--holdout %s" % value, ["info", cap, "--holdout", value], "refused", names="holdout")
        for value in ["0x0", "99999999x1", "64", "-64x48", "64x48x2"]:
            self.judge("flags", "--res %s" % value,
                       ["synth", "builtin:spheres", "-o", os.path.join(self.work, "S"), "--res", value], "refused",
                       names="res")
        for value in ["-1", "0", "99999999999999999999"]:
            self.judge("flags", "--iters %s" % value,
                       ["train", cap, "-o", os.path.join(self.work, "T"), "--iters", value], "refused", names="iters")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--glint", default="build/glint", help="the glint program to try (default build/glint)")
    parser.add_argument("--work", help="scratch folder (default: a new temporary one, removed afterwards)")
    parser.add_argument("--json", help="also write every case and its verdict to this JSON file")
    args = parser.parse_args()
    if not os.access(args.glint, os.X_OK):
        sys.exit("hostile_sweep: %s is not an executable; run make build first" % args.glint)
    work = os.path.abspath(args.work) if args.work else tempfile.mkdtemp(prefix="glint-hostile-")
    os.makedirs(work, exist_ok=True)
    sweep = Sweep(args.glint, work)
    try:
        cap = os.path.join(work, "CAPTURE")
        nerf = os.path.join(work, "NERF")
        run = os.path.join(work, "RUN")
        print("hostile_sweep: making fixtures in %s" % work, file=sys.stderr)
        for command in (["synth", "builtin:spheres", "-o", cap, "--layout", "capture", "--train", "8", "--res", "64x48",
                         "--spp", "8"],
                        ["train", cap, "-o", run, "--iters", "30", "--batch-rays", "512"]):
            code, out = sweep.run(command, timeout=600)
            if code != 0:
                sys.exit("hostile_sweep: fixture command failed: glint %s\n%s" % (" ".join(command), out))
        os.makedirs(os.path.join(nerf, "train"))
        frames = []
        for i in range(3):
            with open(os.path.join(nerf, "train", "r_%d.png" % i), "wb") as f:
                f.write(png_bytes(16, 12, 4, 200))
            frames.append({"file_path": "./train/r_%d" % i,
                           "transform_matrix": [[1, 0, 0, i * 0.1], [0, 1, 0, 0], [0, 0, 1, 4], [0, 0, 0, 1]]})
        with open(os.path.join(nerf, "transforms_train.json"), "w") as f:
            json.dump({"camera_angle_x": 0.69, "frames": frames}, f)
        for step, surface in [("captures", lambda: sweep.captures(cap)), ("priors", lambda: sweep.priors(cap)),
                              ("nerf", lambda: sweep.nerf(nerf)), ("ply", sweep.ply),
                              ("exports", lambda: sweep.exports(run)), ("runs", lambda: sweep.runs(run, cap)),
                              ("flags", lambda: sweep.flags(cap, run))]:
            before = len(sweep.results)
            surface()
            print("hostile_sweep: %-9s %3d cases" % (step, len(sweep.results) - before), file=sys.stderr)
    finally:
        if not args.work:
            shutil.rmtree(work, ignore_errors=True)

    surfaces = sorted({r[0] for r in sweep.results})
    print("| surface | cases | refused | accepted | BAD |")
    print("| --- | --- | --- | --- | --- |")
    for s in surfaces + ["all"]:
        rows = [r for r in sweep.results if s == "all" or r[0] == s]
        count = lambda v: sum(1 for r in rows if r[2] == v)
        print("| %s | %d | %d | %d | %d |" % (s, len(rows), count("refused"), count("accepted"), count("BAD")))
    bad = [r for r in sweep.results if r[2] == "BAD"]
    for surface, name, _, detail in bad:
        print("BAD %s / %s: %s" % (surface, name, detail))
    if args.json:
        with open(args.json, "w") as f:
            json.dump([dict(zip(("surface", "case", "verdict", "detail"), r)) for r in sweep.results], f, indent=1)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
