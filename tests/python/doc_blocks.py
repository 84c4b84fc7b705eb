"""The docs' examples as the docs test (check_docs.py) reads them: the pages
in reading order, each page's fenced blocks, and what each block asks of the
test. docs/testing.md ("The docs' examples") writes the conventions for
readers; in short:

- ```sh (bash, shell) blocks run in one bash per page, in page order, so a
  `cd` or variable of one block reaches the next; every command must exit 0.
- ```console blocks run each `$ ` line; the lines after it are its output,
  each of which must appear in what the command printed (`...` stands for
  lines left out); `$ echo $?` followed by a number is the exit code the
  command before it must end with (without it, 0).
- ```python blocks run under /usr/bin/python3 with python/ on PYTHONPATH; a
  line commented `# prints: TEXT` must have printed the line TEXT;
  blocks that use `self` outside a class are behavior snippets, run by
  doc_snippets.py inside the page's example behavior.
- A ```json block right after a run block is the shape of what it printed:
  each JSON answer printed has the keys of the one shown.
- A block whose prose line before it says "Save this as `FILE`:" (or "and
  this as `FILE` next to it:") is written to FILE instead of being run.
- A block whose first line is `# needs: REASON` (a GPU, a cluster,
  `make install`, ...) is shown but not run; the test lists it with REASON.
- ```text, ```yaml and other blocks are not run."""
import re

RUN_SHELL = {"sh", "bash", "shell"}
RUNS = RUN_SHELL | {"console", "python"}
FENCE = re.compile(r"^( {0,3}|\s*)(`{3,}|~{3,})\s*([^\s`]*)")
SAVE_AS = re.compile(r"(?:save (?:this|it)|and this) as `([^`]+)`[^`]*:\s*$", re.I)
NEEDS = re.compile(r"^\s*(?:#|\$ #)\s*needs:\s*(.+)$", re.I)


class Block:
    """One fenced block: its page, first body line (1-based), language and lines."""

    def __init__(self, page, line, language, body, prose, adjacent):
        self.page, self.line, self.language, self.body = page, line, language, body
        self.text = "\n".join(body) + "\n"
        self.adjacent = adjacent  # only blank lines since the block before
        saved = SAVE_AS.search(prose)
        self.save_as = saved.group(1) if saved else None
        first = next((b for b in body if b.strip()), "")
        needs = NEEDS.match(first)
        self.needs = needs.group(1).strip() if needs else None

    def where(self):
        return f"{self.page}:{self.line}"


def fenced_blocks(page, text):
    """Every fenced block of a page, in order, with the paragraph of prose before it."""
    blocks, lines = [], text.splitlines()
    i, prose, adjacent = 0, "", False
    while i < len(lines):
        opening = FENCE.match(lines[i])
        if not opening:
            if lines[i].strip():  # the paragraph before a block, its lines joined
                joined = i > 0 and lines[i - 1].strip() and not adjacent
                prose, adjacent = (prose + " " + lines[i].strip()) if joined else lines[i], False
            i += 1
            continue
        indent, fence, language = len(opening.group(1)), opening.group(2), opening.group(3).lower()
        start, body = i + 2, []
        i += 1
        while i < len(lines):
            closing = re.match(r"^\s*(`{3,}|~{3,})\s*$", lines[i])
            if closing and closing.group(1)[0] == fence[0] and len(closing.group(1)) >= len(fence):
                break
            line = lines[i]
            body.append(line[min(indent, len(line) - len(line.lstrip(" "))):])  # a block inside a list item
            i += 1
        i += 1
        blocks.append(Block(page, start, language, body, prose, adjacent))
        prose, adjacent = "", True
    return blocks


def reading_order(readme_text, doc_pages):
    """README.md, then the pages in the order of README's "Where to read on"
    table; a page missing from the table is an error (a reader would not find it)."""
    section = readme_text.split("## Where to read on", 1)
    if len(section) != 2:
        raise ValueError("README.md has no '## Where to read on' section listing the pages")
    listed = []
    for name in re.findall(r"^\| \[(docs/[^\]]+\.md)\]", section[1], re.M):
        if name not in listed:
            listed.append(name)
    missing = sorted(set(doc_pages) - set(listed))
    if missing:
        raise ValueError("README.md's 'Where to read on' table does not list " + ", ".join(missing))
    gone = [p for p in listed if p not in doc_pages]
    if gone:
        raise ValueError("README.md's 'Where to read on' table lists missing pages: " + ", ".join(gone))
    return ["README.md"] + listed


def joined_lines(body):
    """(offset, line) with backslash continuations joined, as bash reads them."""
    out, pending, start = [], "", None
    for offset, raw in enumerate(body):
        if start is None:
            start = offset
        if raw.rstrip().endswith("\\"):
            pending += raw.rstrip()[:-1] + "\n"
            continue
        out.append((start, pending + raw))
        pending, start = "", None
    if pending:
        out.append((start, pending))
    return out


class ConsoleStep:
    """A `$ command` of a console block, the output shown after it and its exit code."""

    def __init__(self, offset, command):
        self.offset, self.command, self.shown, self.exit_code = offset, command, [], 0


def console_steps(body):
    """The commands of a ```console block; `$ echo $?` sets the exit code of the one before."""
    steps, awaiting_code = [], False
    for offset, line in joined_lines(body):
        if line.startswith("$ "):
            command = line[2:].strip()
            awaiting_code = command == "echo $?" and bool(steps)
            if not awaiting_code:
                steps.append(ConsoleStep(offset, command))
        elif awaiting_code:
            steps[-1].exit_code = int(line.strip())
            awaiting_code = False
        elif steps and line.strip():
            steps[-1].shown.append(line.rstrip())
    return steps


def json_answers(text):
    """The answers a ```json block shows: each starts at a `{` in column 0.
    `...` where items are left out is dropped so the rest parses."""
    answers, current = [], []
    for line in text.splitlines():
        if line.startswith("{") and current:
            answers.append("\n".join(current))
            current = []
        if line.strip():
            current.append(line)
    if current:
        answers.append("\n".join(current))
    cleaned = []
    for answer in answers:
        answer = re.sub(r",\s*\.\.\.(?=\s*[\]}])", "", answer)
        answer = re.sub(r"(?<=[\[{])\s*\.\.\.\s*,?", "", answer)
        cleaned.append(answer)
    return cleaned
