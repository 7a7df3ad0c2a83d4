"""Pair kinds: what each joint type reads, means and provides, in one place per layer.

A joint type (``revolute``, ``cam``, ``gear`` …) is the unit of design.  Each
layer that treats joints differently by type keeps a registry keyed by
:class:`~mech.model.JointType`, and a test (``tests/test_pair_kinds.py``) walks every
type through every registry, so a new kind is a checklist that fails until
each layer has its entry:

===========================  =====================================  ============================
layer                        registry                               entry provides
===========================  =====================================  ============================
model (this package)         :data:`mech.pairs.registry.KINDS`       keys + schema fragments, a
                                                                    reader giving a typed spec,
                                                                    classification, which links
                                                                    the joint is a point of
kinematics                   :data:`mech.kinematics.rows.ROWS`       constraint rows (named
                                                                    records), curvature terms
                                                                    come with each row type
I-centres                    :data:`mech.icentres.inspection.RULES`  the I-centre by inspection
drawing                      :data:`mech.draw.config.GLYPHS`         the glyph drawn at the joint
===========================  =====================================  ============================

This ``__init__`` imports nothing, so that :mod:`mech.model` can use the spec
types of :mod:`mech.pairs.specs` without a cycle; the registry lives in
:mod:`mech.pairs.registry`.
"""
