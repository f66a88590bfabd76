// headlight diff command: written by the diff work (issue 4).
