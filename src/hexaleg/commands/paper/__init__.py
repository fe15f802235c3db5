"""``hexaleg paper``: the paper's single joint reproduced and its files written."""
