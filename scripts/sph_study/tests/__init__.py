"""Unit tests of sph_study (no runs of the sph program):
    cd scripts && /usr/bin/python3 -m unittest discover -s sph_study/tests -t ."""
