"""The rollout stage's media folder holds exactly this study's files; the rest waits beside the store."""

from __future__ import annotations

from types import SimpleNamespace

from ladev_lib.rollout.stage import keep_only_this_studys_media


def row(eid: str, video: bool = False) -> SimpleNamespace:
    return SimpleNamespace(
        first_frame_path=f"data/media/toy/{eid}_first.png",
        last_frame_path=f"data/media/toy/{eid}_last.png",
        video_path=f"data/media/toy/{eid}.mp4" if video else None,
    )


def test_files_of_episodes_no_longer_planned_leave_and_come_back(tmp_path):
    media, archive = tmp_path / "media", tmp_path / "store" / "media"
    media.mkdir()
    for name in ("a_first.png", "a_last.png", "b_first.png", "b_last.png", "b.mp4", ".gitignore"):
        (media / name).write_text(name)

    keep_only_this_studys_media(media, archive, [row("a")])  # the study shrank to episode a
    assert sorted(p.name for p in media.iterdir()) == [".gitignore", "a_first.png", "a_last.png"]
    assert sorted(p.name for p in archive.iterdir()) == ["b.mp4", "b_first.png", "b_last.png"]

    keep_only_this_studys_media(media, archive, [row("a"), row("b", video=True)])  # and grew back
    assert sorted(p.name for p in media.iterdir()) == [
        ".gitignore", "a_first.png", "a_last.png", "b.mp4", "b_first.png", "b_last.png",
    ]
    assert (media / "b.mp4").read_text() == "b.mp4" and not any(archive.iterdir())
