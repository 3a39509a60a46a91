// placeholder so the library target exists until the stage lands
