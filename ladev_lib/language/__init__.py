"""Instructions: the basic form, paraphrases, and their validation."""
