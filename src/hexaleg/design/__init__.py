"""Layer 7 — spring design, in the order the data flows: the paper's rules (``rules``), a
gait's metrics (``evaluator``), the spring families (``families/``), the programs and their
searches (``search/``), the physical spring (``springs/``), designs over a box of conditions
(``robust/``), the one-class studies (``studies/``), the staged design (``chain/``), the gait and
springs together (``codesign/``) and the fold (``fold``)."""
