"""The paper's side of the reproduction: the claims checked against its printed values, the
alternative readings of the paper, the explanations, the tables and the reproduction report."""
