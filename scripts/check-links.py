#!/usr/bin/env python3
"""Check that every relative link in README.md and docs/**/*.md resolves.

A link resolves when its file exists (relative to the page) and, for a link with an anchor
into a Markdown page, when that page has a heading with that anchor (mdBook's and GitHub's
rule: the heading's text, lower case, spaces to hyphens, other punctuation dropped).
mdBook's `{{#include FILE}}` is checked as a link. Links inside code are ignored.
Every page under docs/ must also be in the book: listed in docs/SUMMARY.md.
Usage: python3 scripts/check-links.py [--allow-missing PATH ...]; exits 1 on a broken link.
"""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LINK = re.compile(r'!?\[(?:[^\]\[]|\[[^\]]*\])*\]\(([^)\s]+)(?:\s+"[^"]*")?\)')
INCLUDE = re.compile(r'\{\{#include\s+([^}\s]+)\s*\}\}')
HEADING = re.compile(r'^(#{1,6})\s+(.*?)\s*#*\s*$')


def strip_code(text):
    """The text with fenced code blocks and inline code spans blanked out."""
    text = re.sub(r'^```.*?^```', '', text, flags=re.S | re.M)
    return re.sub(r'`[^`\n]*`', '``', text)


def anchor(heading):
    """The anchor mdBook (and GitHub) gives a heading."""
    heading = re.sub(r'\[([^\]]*)\]\([^)]*\)', r'\1', heading)
    heading = heading.replace('`', '').replace('*', '')
    out = []
    for ch in heading:
        if ch.isalnum() or ch in '_-':
            out.append(ch.lower())
        elif ch.isspace():
            out.append('-')
    return ''.join(out)


def anchors(path):
    """Every anchor a Markdown file's headings define."""
    seen = {}
    result = set()
    text = re.sub(r'^```.*?^```', '', open(path, encoding='utf-8').read(), flags=re.S | re.M)
    for line in text.split('\n'):
        m = HEADING.match(line)
        if not m:
            continue
        a = anchor(m.group(2))
        n = seen.get(a, 0)
        seen[a] = n + 1
        result.add(a if n == 0 else f'{a}-{n}')
    return result


def pages():
    yield os.path.join(ROOT, 'README.md')
    for dirpath, _, files in os.walk(os.path.join(ROOT, 'docs')):
        for f in sorted(files):
            if f.endswith('.md'):
                yield os.path.join(dirpath, f)


def main():
    allowed = set(sys.argv[sys.argv.index('--allow-missing') + 1:]) if '--allow-missing' in sys.argv else set()
    broken = 0
    checked = 0
    for page in pages():
        raw = open(page, encoding='utf-8').read()
        targets = LINK.findall(strip_code(raw)) + INCLUDE.findall(raw)
        for target in targets:
            if re.match(r'^[a-z][a-z0-9+.-]*:', target):  # http:, https:, mailto:
                continue
            checked += 1
            path, _, frag = target.partition('#')
            file = os.path.normpath(os.path.join(os.path.dirname(page), path)) if path else page
            rel = os.path.relpath(file, ROOT)
            where = os.path.relpath(page, ROOT)
            if not os.path.exists(file):
                if rel in allowed:
                    print(f'{where}: {target}: missing, allowed')
                    continue
                print(f'{where}: {target}: no such file')
                broken += 1
            elif frag and file.endswith('.md') and frag not in anchors(file):
                print(f'{where}: {target}: no heading with anchor #{frag} in {rel}')
                broken += 1
    summary = os.path.join(ROOT, 'docs', 'SUMMARY.md')
    listed = {os.path.normpath(os.path.join(os.path.dirname(summary), t.partition('#')[0]))
              for t in LINK.findall(strip_code(open(summary, encoding='utf-8').read()))}
    for page in pages():
        if page.startswith(os.path.join(ROOT, 'docs')) and page != summary and page not in listed:
            print(f'{os.path.relpath(page, ROOT)}: not listed in docs/SUMMARY.md, so not in the book')
            broken += 1
    print(f'{checked} relative links checked, {broken} broken')
    return 1 if broken else 0


if __name__ == '__main__':
    sys.exit(main())
