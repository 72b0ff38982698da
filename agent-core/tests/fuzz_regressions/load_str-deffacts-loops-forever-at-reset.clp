(deffacts start (go (while qoda * 1)))
