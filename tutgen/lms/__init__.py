"""LMS exports of a sheet: Moodle XML (``-f moodle``) and an IMS QTI 2.1 package (``-f qti``).

The sheet's build gathers, per problem and variant, a :class:`tutgen.lms.questions.LmsQuestion`
(plain data: the question and the worked solution as Markdown, the figure, the graded results as the
answer key has them); :mod:`tutgen.lms.moodle` and :mod:`tutgen.lms.qti` write the exports from them,
and :mod:`tutgen.lms.readback` reads the answers back out of an export (the round-trip tests).
docs/lms.md says what an instructor gets in each system.
"""
