#!/usr/bin/env python3
"""The pictures of docs/authoring.md, made by the headless renderer: bodyview --author
replays the walkthrough's clicks and keys (kiosk/app/replay.h's format) on six regions of
the AAL atlas, one replay per picture, each the one before plus its step.

usage: scripts/authoring_pictures.py BODYVIEW MODELS_DIR OUT_DIR
  MODELS_DIR: the atlas's per-structure meshes (e.g. a `bodygen exhibit` bundle's models/)
"""
import os
import shutil
import subprocess
import sys

ROW = 26  # panel row height at 1280x800 (kiosk/author/panel.cpp); value boxes centred at x 284
MODELS = ["Hippocampus_L", "Hippocampus_R", "Amygdala_L", "Amygdala_R", "Caudate_L", "Caudate_R"]


class Script:
    def __init__(self):
        self.lines, self.t = ["size 1280 800"], 0.2

    def click(self, x, y, mods=""):
        self.lines += [f"{self.t:.2f} mouse-down left {x} {y} {mods}", f"{self.t + 0.02:.2f} mouse-up left {x} {y} {mods}"]
        self.t += 0.1

    def row(self, i, x=284, mods=""):
        self.click(x, ROW * i + 13, mods)

    def key(self, k, mods=""):
        self.lines.append(f"{self.t:.2f} key {k} {mods}")
        self.t += 0.05

    def type(self, text):
        self.lines += [f"{self.t:.2f} text {ord(c)}" for c in text]
        self.t += 0.05

    def set(self, i, text, mods=""):  # a field: focus (Shift: type a choice), select all, type, Enter
        self.row(i, mods=mods)
        self.key(ord("A"), "ctrl")
        self.type(text)
        self.key(265)

    def text(self):
        return "\n".join(self.lines + [f"{self.t + 0.2:.2f} end"]) + "\n"


def steps():
    s = Script()
    s.click(840, 400)  # 1: the six meshes opened as a new scene; one selected
    yield "authoring_1_open", s
    s.key(256)  # Esc: nothing selected, the scene's fields
    s.set(24, "en de")  # languages: English and German
    s.row(11, 100)  # Add group: "group 1", selected
    s.set(16, "Limbic system")  # its name
    s.set(17, "hatching", "shift")  # its style (Shift+click types a choice)
    s.row(5, 100)  # Hippocampus_L
    s.row(18)  # its group: none -> Limbic system
    s.row(6, 100)  # Hippocampus_R (the group closes: rows move up one)
    s.row(17)  # its group
    yield "authoring_2_grouped", s
    s.row(4, 100)  # Hippocampus_L, under the open group
    s.set(26, "Hippocampus (left)")  # title [en]
    s.set(28, "Hippocampus (links)")  # title [de]
    s.set(29, "Gedächtnis und Orientierung")  # description [de]
    yield "authoring_3_bilingual", s


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    bodyview, models, out = sys.argv[1:]
    work = os.path.join(out, "authoring_work")
    files = [os.path.join(models, m + ".bpm") for m in MODELS]
    for name, s in steps():
        shutil.rmtree(work, ignore_errors=True)
        os.makedirs(work)
        replay = os.path.join(work, name + ".replay")
        with open(replay, "w") as f:
            f.write(s.text())
        subprocess.run([bodyview, "--author", os.path.join(work, "exhibit") + "/", *files, "--headless", "--size",
                        "1280x800", "--replay", replay, "--screenshot", os.path.join(out, name + ".png")], check=True)
    # 4: saved and shown as visitors get it (P), with the German title.
    s.key(ord("S"), "ctrl")
    s.key(ord("P"))
    replay = os.path.join(work, "authoring_4_preview.replay")
    with open(replay, "w") as f:
        f.write(s.text())
    subprocess.run([bodyview, "--author", os.path.join(work, "exhibit") + "/", *files, "--headless", "--size", "1280x800",
                    "--replay", replay, "--preview-screenshot", os.path.join(out, "authoring_4_preview.png")], check=True)
    shutil.rmtree(work)


if __name__ == "__main__":
    main()
