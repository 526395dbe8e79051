"""A learned span tagger: which words of a scene description say what.

The reader's learned half. A small encoder (all-MiniLM-L6-v2, the embedding
model the project already ships) with low-rank adapters and a tagging head
marks, in a description, the phrases that put objects in the scene, the task's
object, destination and relation, positions, and the lighting and camera
requests that still hold after the writer's corrections. The rule readers then
read values (counts, amounts, directions, catalog names) from the marked
phrases only: :mod:`ladev_lib.language.scene.tagged` assembles the scene.

    tagger = load_tagger()                     # the committed weights
    spans = tagger.tag("a bowl - no, make that a basket; put the plum in it")

Training: ``ladev train-reader`` (:mod:`ladev_lib.language.tagging.training`)
on annotated rows (:mod:`ladev_lib.language.tagging.markup`).
"""

from ladev_lib.language.tagging.markup import TAGS, Span, parse_markup

__all__ = ["TAGS", "Span", "parse_markup"]
