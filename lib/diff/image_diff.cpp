// headlight diff: written by the diff work (issue 4).
