# Install/uninstall the ACTIVEGRAIN package's files in LAMMPS's src/ (legacy make build)
# mode = 0/1/2 for uninstall/install/update, as for LAMMPS's own packages

mode=$1

# enforce using portable C locale
LC_ALL=C
export LC_ALL

# fix rigid/rod is a fix rigid/small (RIGID); the package's decks and examples use GRANULAR's
# fixes (pour, freeze) beside our styles.

if (test $mode = 1) then
  if (test ! -e ../fix_rigid_small.cpp) then
    echo "Must install RIGID package with ACTIVEGRAIN"
    exit 1
  fi
  if (test ! -e ../fix_pour.cpp) then
    echo "Must install GRANULAR package with ACTIVEGRAIN"
    exit 1
  fi
fi

for file in *.cpp *.h; do
  if (test $mode = 0) then
    rm -f ../$file
  elif (! cmp -s $file ../$file) then
    cp $file ..
    if (test $mode = 2) then
      echo "  updating src/$file"
    fi
  fi
done
