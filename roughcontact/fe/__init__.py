"""The seed's finite-element fingertip (Figs. 6–7, Eq. 34) and its contact-length reduction fed to the
friction law (Eqs. 43–44). Optional: ``pip install "roughcontact[fe]"``.

Licence note. The code of this subpackage is MIT-licensed like the rest of roughcontact. Its model
(:mod:`roughcontact.fe.model`) runs on FElupe, which is GPL-3.0-or-later; FElupe is not a dependency of
roughcontact but of the optional extra ``fe``, and it is imported only inside the functions that build and solve
the model. Nothing outside this subpackage imports it, nor do :mod:`~roughcontact.fe.geometry`,
:mod:`~roughcontact.fe.analysis` and :mod:`~roughcontact.fe.feed` (numpy only: the friction law reads the FE
study's table without FElupe). Whoever distributes a program together with FElupe takes on the GPL's terms for
that combination.

Modules: ``geometry`` (the parametric section and its mesh), ``materials`` (Ogden tissues), ``model`` (the FE
model and its press-and-slide protocol), ``analysis`` (contact length, Eq. 34 fit, power laws), ``study``
(the sweep over f_N and the outputs of ``roughcontact fingertip-fe``), ``feed`` (the area reduction of the
friction law). See ``docs/guide/fe_fingertip.md``.
"""
