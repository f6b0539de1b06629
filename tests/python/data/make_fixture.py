#!/usr/bin/python3
"""Regenerate small_scene.dump.gz: a ~600-disc cover-over-salt scene over a
basement normal fault at 0, 50, 100 and 150 m of slip, in the decks' dump
format (columns id type x y vx vy radius i_marker, atoms unsorted).

From the repository root, with the checkout's package on the module path (or
the package installed, see the README):

  PYTHONPATH=python /usr/bin/python3 tests/python/data/make_fixture.py
"""
import os

from saltdem_post.synthetic import write_fixture

HERE = os.path.dirname(os.path.abspath(__file__))

if __name__ == "__main__":
    frames = write_fixture(os.path.join(HERE, "small_scene.dump.gz"))
    print(f"wrote {len(frames)} frames of {frames[0].natoms} discs")
