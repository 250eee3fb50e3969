#!/usr/bin/env python3
"""The commands of the README's and the user guide's shell blocks, run in order
as a reader would type them (ctest: Docs.CommandsRunInOrder).

    doc_commands.py SOURCE_DIR BUILD_DIR [DOC ...]   (default README.md docs/user-guide.md)

Every ```sh block of each document, in document order; a line ending in a
backslash continues on the next; `# ...` comments are dropped. Each command runs
in one fresh temporary folder that holds links to the repository's inputs
(scenes/, validation/, examples/) and `build` (the build folder), so that the
commands' relative paths work and their outputs (out/...) land in the
temporary folder, never in the source tree. `evas` is the built program (on
PATH), and mpirun may run as root (CI). `make demo` and `make test` are not run
here: they are what runs this.

A command that exits non-zero, names a file that no earlier command wrote (a
placeholder such as out/x/...), or holds `...` fails the test with the
document, its line and the command's output.
"""
import os
import re
import shlex
import subprocess
import sys
import tempfile
import time


def commands(path):
    """(line, command) of every ```sh block: continuation lines joined, comments
    dropped (the command re-quoted word by word, as the shell would read it)."""
    out, block, pending, start = [], False, "", 0
    with open(path, encoding="utf-8") as f:
        for no, raw in enumerate(f, 1):
            line = raw.rstrip()
            if line.startswith("```"):
                block = (not block) and line in ("```sh", "```bash")
                continue
            if not block:
                continue
            if not pending:
                start = no
            if line.endswith("\\"):
                pending += line[:-1] + " "
                continue
            words = shlex.split(pending + line, comments=True)
            pending = ""
            if words:
                out.append((start, shlex.join(words)))
    return out


def main():
    src, build = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    docs = sys.argv[3:] or ["README.md", "docs/user-guide.md"]
    work = tempfile.mkdtemp(prefix="evas-doc-commands-")
    for name in ("scenes", "validation", "examples"):
        os.symlink(os.path.join(src, name), os.path.join(work, name))
    os.symlink(build, os.path.join(work, "build"))
    env = dict(os.environ)
    env["PATH"] = build + os.pathsep + env.get("PATH", "")
    env.update(
        OMPI_ALLOW_RUN_AS_ROOT="1",
        OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
        OMPI_MCA_rmaps_base_oversubscribe="1",
        TMPDIR=work,
    )
    failures, ran = [], 0
    for doc in docs:
        for line, cmd in commands(os.path.join(src, doc)):
            where = "%s:%d" % (doc, line)
            if re.match(r"^make\b", cmd):
                print("skip  %s  %s  (the target that runs this test)" % (where, cmd))
                continue
            if "..." in cmd:
                failures.append("%s: `%s` holds a placeholder '...'" % (where, cmd))
                continue
            # an input under out/ must have been written by an earlier command
            words = shlex.split(cmd)
            missing = [
                w
                for i, w in enumerate(words)
                if w.startswith("out/")
                and w.endswith((".h5", ".yaml", ".csv"))
                and (i == 0 or words[i - 1] not in ("-o", "--out", "--csv"))
                and not os.path.exists(os.path.join(work, w))
            ]
            if missing:
                failures.append(
                    "%s: `%s` reads %s, which no earlier command wrote" % (where, cmd, missing)
                )
                continue
            t0 = time.time()
            r = subprocess.run(
                cmd, shell=True, cwd=work, env=env, capture_output=True, text=True, timeout=900
            )
            ran += 1
            print("%5.1f s  exit %d  %s  %s" % (time.time() - t0, r.returncode, where, cmd))
            if r.returncode != 0:
                failures.append(
                    "%s: `%s` exited %d:\n%s"
                    % (where, cmd, r.returncode, (r.stdout + r.stderr)[-3000:])
                )
    # the outputs stay in the temporary folder: nothing was written elsewhere
    subprocess.run(["rm", "-rf", work])
    print("%d commands run, %d failures" % (ran, len(failures)))
    for f in failures:
        print("FAIL " + f)
    return 1 if failures or ran == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
