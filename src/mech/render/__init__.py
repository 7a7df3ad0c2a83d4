"""Reports made from analysis results: rich tables for people, JSON for machines.

Analyses never print and never import rich; everything a user reads is made
here, from the same result objects that ``--json`` serialises, so the table
and the JSON cannot disagree.
"""
