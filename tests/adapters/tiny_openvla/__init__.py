"""Remote code of a tiny OpenVLA stand-in checkpoint (test fixture; see ``build.py``)."""
