"""Instructions: the basic form, paraphrases, and their validation.

- ``instructions``: the basic instruction ("put the carrot on the plate").
- ``parser`` (with ``tokens``, ``clauses``, ``mentions``, ``lexicon``): read an
  instruction back into (task, source, target), or say why it cannot be.
- ``paraphrase``: the offline compositional paraphraser.
- ``validator``: similarity AND structural round-trip, per candidate.
- ``llm_jobs`` / ``offline_jobs``: the ``paraphrase`` and ``parse_instruction`` jobs.
- ``pipeline``: the paraphrase stage's logic; ``config``: its ``paraphrase:`` section.
- ``evaluation``: precision / recall of "valid" on labelled pairs.
- ``embeddings``: the sentence-embedding model, loaded once per process.
"""
