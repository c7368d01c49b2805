#!/usr/bin/env python3
"""Remove <visual>, <transmission>, <gazebo> and <ros2_control> elements from a URDF.

Text-level removal so that everything else (collision geometry, joints, limits, link names,
comments, number formatting) stays byte-for-byte as published. A structural check with
ElementTree confirms the result equals the original tree minus exactly those elements.

usage: strip_urdf.py IN.urdf OUT.urdf "header comment text" [LINK ...]

Each LINK named after the header also loses its <collision> elements (used for one degenerate
zero-length cylinder in the Franka test URDF).
"""
import re
import sys
import xml.etree.ElementTree as ET

TAGS = ("visual", "transmission", "gazebo", "ros2_control")


def strip(text):
    counts = {}
    for tag in TAGS:
        # self-closing element on its own line(s)
        pat_empty = re.compile(r"^[ \t]*<%s\b[^>]*/>[ \t]*\n" % tag, re.M)
        # element with content (these tags never nest inside themselves in URDF)
        pat_full = re.compile(r"^[ \t]*<%s\b[^>]*(?<!/)>.*?</%s>[ \t]*\n" % (tag, tag), re.M | re.S)
        text, n1 = pat_empty.subn("", text)
        text, n2 = pat_full.subn("", text)
        counts[tag] = n1 + n2
    return text, counts


def drop_link_collisions(text, link):
    pat = re.compile(r'(<link name="%s">.*?</link>)' % re.escape(link), re.S)
    m = pat.search(text)
    assert m, link
    body, n = re.subn(r"^[ \t]*<collision\b[^>]*>.*?</collision>[ \t]*\n", "", m.group(1), flags=re.M | re.S)
    assert n >= 1, link
    return text[: m.start()] + body + text[m.end():]


def remove_from_tree(elem, links=()):
    if elem.tag == "link" and elem.get("name") in links:
        for child in list(elem):
            if child.tag == "collision":
                elem.remove(child)
    for child in list(elem):
        if child.tag in TAGS:
            elem.remove(child)
        else:
            remove_from_tree(child, links)


def canon(elem):
    # tag, attributes and stripped text, recursively (comments are dropped by ET's default parser)
    return (elem.tag, sorted(elem.attrib.items()), (elem.text or "").strip(),
            [canon(c) for c in elem])


def main():
    src, dst, header, links = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
    text = open(src, encoding="utf-8").read()
    out, counts = strip(text)
    for link in links:
        out = drop_link_collisions(out, link)
    # insert the header comment after the XML declaration
    m = re.match(r"<\?xml[^>]*\?>\n", out)
    assert m, "no XML declaration"
    out = out[: m.end()] + "<!--\n" + header.rstrip() + "\n-->\n" + out[m.end():]
    # structural check
    orig = ET.fromstring(text.encode())
    remove_from_tree(orig, links)
    new = ET.fromstring(out.encode())
    assert canon(orig) == canon(new), "structural mismatch"
    for tag in TAGS:
        assert ("<" + tag) not in re.sub(r"<!--.*?-->", "", out, flags=re.S), tag
    open(dst, "w", encoding="utf-8").write(out)
    print(src, "->", dst, counts, "collisions dropped from", links)


if __name__ == "__main__":
    main()
